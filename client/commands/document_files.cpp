#include "client/commands/document_files.hpp"

#include <map>
#include <stdexcept>

#include "core/util/atomic_file.hpp"

namespace meshmark::cli {

namespace fs = std::filesystem;

namespace {

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

std::string contents_of(const fs::path& path) { return read_file_bytes(path, std::size_t{8} << 30); }

}  // namespace

void check_output(const fs::path& in, const fs::path& out, const MeshDocument& document) {
  std::vector<fs::path> inputs = {in};
  for (const std::string& uri : document.companions()) inputs.push_back(in.parent_path() / percent_decoded(uri));
  for (const fs::path& input : inputs)
    if (same_file(out, input) || out.lexically_normal() == input.lexically_normal())
      throw std::runtime_error(out.string() +
                               ": writing it would overwrite the original; choose another output name or folder");
  const MeshFormat format = mesh_format_from_path(out);
  if (format != document.format() &&
      (format == MeshFormat::glb || format == MeshFormat::gltf || format == MeshFormat::threemf))
    throw std::runtime_error(out.string() + ": a marked " + to_string(format) + " comes only from a " +
                             to_string(format) + " original; write " + to_string(document.format()) +
                             ", or a plain obj, off, ply or stl mesh");
}

CompanionNames companion_names(const fs::path& in, const fs::path& out) {
  const std::string in_stem = in.stem().string(), out_stem = out.stem().string();
  return [in_stem, out_stem](const std::string& uri) {
    const fs::path name = fs::path(percent_decoded(uri)).filename();
    return name.stem().string() == in_stem ? out_stem + name.extension().string() : out_stem + "_" + name.string();
  };
}

std::vector<fs::path> write_document_files(const fs::path& in, const fs::path& out, const MeshDocument& document,
                                           const DocumentFiles& files) {
  const fs::path in_dir = in.parent_path(), out_dir = out.parent_path();
  // What goes where: the main file, the changed companions, and the unchanged ones when the
  // output is in another folder (never one the copy replaced under a new name: that is the
  // unmarked original).
  std::map<fs::path, std::string> plan;
  plan[out] = files.at("");
  for (const auto& [name, bytes] : files)
    if (!name.empty()) plan[out_dir / percent_decoded(name)] = bytes;
  std::map<fs::path, bool> copied;  // unchanged companions: must not replace a different file
  const CompanionNames renamed = companion_names(in, out);
  if (!same_file(in_dir.empty() ? "." : in_dir, out_dir.empty() ? "." : out_dir))
    for (const std::string& uri : document.companions()) {
      const fs::path source = in_dir / percent_decoded(uri), target = out_dir / percent_decoded(uri);
      if (plan.count(target) || files.count(renamed(uri)) || !fs::exists(source)) continue;
      if (fs::exists(target) && contents_of(target) == contents_of(source)) continue;
      plan[target] = contents_of(source);
      copied[target] = true;
    }
  // Checked before anything is written.
  std::vector<fs::path> inputs = {in};
  for (const std::string& uri : document.companions()) inputs.push_back(in_dir / percent_decoded(uri));
  for (const auto& [target, bytes] : plan) {
    for (const fs::path& input : inputs)
      if (same_file(target, input) || target.lexically_normal() == input.lexically_normal())
        throw std::runtime_error(target.string() +
                                 ": writing it would overwrite the original; choose another output name or folder");
    if (copied.count(target) && fs::exists(target))
      throw std::runtime_error(target.string() +
                               " exists and differs from what the marked copy needs there; "
                               "choose another output folder");
  }
  // Companions first, the main file last: it never refers to a file not yet written.
  std::vector<fs::path> written;
  const auto put = [&](const fs::path& target, const std::string& bytes) {
    if (!target.parent_path().empty()) fs::create_directories(target.parent_path());
    write_file_atomically(target, bytes);
    written.push_back(target);
  };
  for (const auto& [target, bytes] : plan)
    if (target != out) put(target, bytes);
  put(out, plan.at(out));
  return written;
}

}  // namespace meshmark::cli
