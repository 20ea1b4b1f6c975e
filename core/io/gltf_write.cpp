// Writing a glTF document back: positions into their own accessors and types (a quantized mesh
// shifted, its nodes taking the shift back, where positions would leave their range), normals and
// tangents turned, Draco streams encoded again with the views after them moved, accessor bounds,
// and the container or the files rebuilt around the edited JSON.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <tuple>

#include "core/io/base64.hpp"
#include "core/io/gltf_components.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/number_text.hpp"

namespace meshmark::gltf {

void GltfDocument::set_bounds(std::size_t accessor, const Eigen::Vector4d& lo, const Eigen::Vector4d& hi,
                              int components, int type, ByteEdits& edits) const {
  const auto text = [&](const Eigen::Vector4d& v) {
    std::string s = "[";
    for (int k = 0; k < components; ++k) {
      if (k) s += ",";
      s += type == kFloat ? number_text(static_cast<float>(v[k])) : std::to_string(static_cast<long long>(v[k]));
    }
    return s + "]";
  };
  const std::string base = "/accessors/" + std::to_string(accessor);
  for (const auto& [key, value] : {std::pair{std::string("min"), lo}, std::pair{std::string("max"), hi}}) {
    if (spans_->has(base + "/" + key)) edits.replace(spans_->value(base + "/" + key), text(value));
    else {
      const std::size_t at = spans_->object_start(base);
      edits.replace({at, at}, "\"" + key + "\":" + text(value) + ",");
    }
  }
}

void GltfDocument::set_member(const std::string& object, const std::string& key, std::uint64_t value,
                              ByteEdits& edits) const {
  if (spans_->has(object + "/" + key)) {
    edits.replace(spans_->value(object + "/" + key), std::to_string(value));
  } else {
    const std::size_t at = spans_->object_start(object);
    edits.replace({at, at}, "\"" + key + "\":" + std::to_string(value) + ",");
  }
}

// The bytes that writing may change (every element of the POSITION, NORMAL and TANGENT accessors
// of the slots) must hold nothing else: not two of those accessors at once, not another accessor's
// element, sparse indices or a view no accessor describes (images, Draco streams). Files built
// otherwise (overlapping views) cannot be marked without changing more than positions.
std::string GltfDocument::aliasing_problem() const {
  struct Span {
    int buffer;
    std::size_t begin, end;
    long owner;
  };
  std::set<std::size_t> written;
  for (const PositionSource& s : position_sources_) written.insert(s.accessor);
  for (const Primitive& p : primitives_)
    if (p.position_source >= 0)
      for (const int a : {p.normal, p.tangent})
        if (a >= 0) written.insert(static_cast<std::size_t>(a));
  std::vector<Span> mine, others;
  std::set<std::size_t> described;  // views some accessor reads
  const Json& accessors = json_.value("accessors", Json::array());
  for (std::size_t a = 0; a < accessors.size(); ++a) {
    const Layout l = layout_of(a);
    const std::size_t size = l.element;
    std::vector<Span>& into = written.count(a) ? mine : others;
    const long owner = written.count(a) ? static_cast<long>(a) : -1;
    if (accessors[a].contains("bufferView")) described.insert(index_of(accessors[a], "bufferView"));
    for (std::size_t i = 0; i < l.count; ++i) {
      if (const auto sp = l.sparse.find(static_cast<std::uint32_t>(i)); sp != l.sparse.end())
        into.push_back({l.sparse_buffer, sp->second, sp->second + size, owner});
      else if (l.buffer >= 0)
        into.push_back({l.buffer, l.offset + i * l.stride, l.offset + i * l.stride + size, owner});
    }
    if (accessors[a].contains("sparse")) {
      const Json& sparse = accessors[a]["sparse"];
      for (const char* part : {"indices", "values"}) {
        const std::size_t v = index_of(sparse.at(part), "bufferView");
        described.insert(v);
        const View view = view_of(v);
        if (std::string(part) == "indices") others.push_back({view.buffer, view.offset, view.offset + view.length, -1});
      }
    }
  }
  const Json& views = json_.value("bufferViews", Json::array());
  for (std::size_t v = 0; v < views.size(); ++v)
    if (!described.count(v)) {
      const View view = view_of(v);
      others.push_back({view.buffer, view.offset, view.offset + view.length, -1});
    }
  const auto by_place = [](const Span& x, const Span& y) {
    return std::tie(x.buffer, x.begin) < std::tie(y.buffer, y.begin);
  };
  std::sort(mine.begin(), mine.end(), by_place);
  const char* const problem =
      "its positions, normals or tangents share bytes with other data (overlapping buffer views)";
  // Two written accessors overlapping: the latest-starting of any such pair meets a running end.
  std::vector<Span> merged;
  for (const Span& w : mine) {
    if (!merged.empty() && merged.back().buffer == w.buffer && w.begin < merged.back().end) {
      if (merged.back().owner != w.owner) return problem;
      if (w.end > merged.back().end) merged.back().end = w.end;
      continue;
    }
    merged.push_back(w);
  }
  for (const Span& o : others) {
    auto it = std::upper_bound(merged.begin(), merged.end(), o, by_place);
    if (it != merged.end() && it->buffer == o.buffer && it->begin < o.end) return problem;
    if (it != merged.begin() && std::prev(it)->buffer == o.buffer && std::prev(it)->end > o.begin) return problem;
  }
  return "";
}

// The accessor's min and max over its elements as they are stored now (normalized integers in
// stored units, as glTF wants them).
void GltfDocument::update_bounds(std::size_t accessor, const std::vector<Buffer>& buffers, ByteEdits& edits) const {
  const Layout l = layout_of(accessor);
  Eigen::Vector4d lo = Eigen::Vector4d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < l.count; ++i) {
    Eigen::Vector4d e = element(l, i, buffers);
    if (l.normalized) e /= stored_range(l.component_type, true).step;
    lo = lo.cwiseMin(e);
    hi = hi.cwiseMax(e);
  }
  set_bounds(accessor, lo, hi, l.components, l.component_type, edits);
}

// Positions move in their accessors' mesh space. Integer (quantized) positions that would leave
// their type's range (gltfpack's start at 0) take the whole mesh along by a shift that its nodes
// take back (mesh_shifts, shift_nodes), so no position is clamped.
void GltfDocument::write_positions(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const {
  std::vector<std::vector<Eigen::Vector3d>> targets(position_sources_.size());
  std::vector<std::vector<char>> moved(position_sources_.size());
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const Matrix4 inverse = s.world.inverse();
    moved[n].assign(l.count, 0);
    for (std::size_t i = 0; i < l.count; ++i) {
      const auto slot = static_cast<Eigen::Index>(s.first_slot + i);
      if (P.row(slot) == positions_.row(slot) || !inverse.allFinite()) {
        targets[n].push_back(element(l, i, buffers_).head<3>());
      } else {
        targets[n].push_back((inverse * P.row(slot).transpose().homogeneous()).head<3>());
        moved[n][i] = 1;
      }
    }
  }
  const std::map<std::size_t, Eigen::Vector3d> shifts = mesh_shifts(targets);
  shift_nodes(shifts, json_edits);
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const auto shift = shifts.find(s.mesh);
    bool changed = false;
    for (std::size_t i = 0; i < l.count; ++i) {
      if (!moved[n][i] && shift == shifts.end()) continue;
      unsigned char* place = element_place(l, i, buffers);
      if (!place)
        throw MeshIoError(source_ + ": accessor " + std::to_string(s.accessor) + " has no storage for its element " +
                          std::to_string(i));
      const Eigen::Vector3d local = targets[n][i] + (shift == shifts.end() ? Eigen::Vector3d::Zero() : shift->second);
      for (int k = 0; k < 3; ++k)
        encode_component(place + k * component_bytes(l.component_type), l.component_type, l.normalized, local[k]);
      changed = true;
    }
    if (changed) update_bounds(s.accessor, buffers, json_edits);
  }
}

// Per mesh whose integer positions would leave their range: the shift (mesh space, a whole number
// of steps) that brings every position accessor of the mesh back inside. Throws when the range is
// too narrow for the marked extent.
std::map<std::size_t, Eigen::Vector3d> GltfDocument::mesh_shifts(
    const std::vector<std::vector<Eigen::Vector3d>>& targets) const {
  const double inf = std::numeric_limits<double>::infinity();
  std::map<std::size_t, std::pair<Eigen::Vector3d, Eigen::Vector3d>> allowed;  // mesh → shift interval
  std::map<std::size_t, double> step;
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const StoredRange range = stored_range(l.component_type, l.normalized);
    auto& [lo, hi] =
        allowed.try_emplace(s.mesh, Eigen::Vector3d::Constant(-inf), Eigen::Vector3d::Constant(inf)).first->second;
    if (range.step == 0) continue;
    step[s.mesh] = std::max(step[s.mesh], range.step);
    for (const Eigen::Vector3d& t : targets[n]) {
      lo = lo.cwiseMax(Eigen::Vector3d::Constant(range.lo) - t);
      hi = hi.cwiseMin(Eigen::Vector3d::Constant(range.hi) - t);
    }
  }
  std::map<std::size_t, Eigen::Vector3d> shifts;
  for (const auto& [mesh, interval] : allowed) {
    const auto& [lo, hi] = interval;
    if ((lo.array() <= 0).all() && (hi.array() >= 0).all()) continue;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      if (lo[k] > 0) d[k] = std::ceil(lo[k] / step[mesh] - 1e-9) * step[mesh];
      else if (hi[k] < 0) d[k] = std::floor(hi[k] / step[mesh] + 1e-9) * step[mesh];
      if (d[k] < lo[k] - 1e-12 || d[k] > hi[k] + 1e-12)
        throw MeshIoError(source_ + ": the marked positions of mesh " + std::to_string(mesh) +
                          " span more than its quantized POSITION type can hold");
    }
    shifts[mesh] = d;
  }
  return shifts;
}

// Nodes that place a shifted mesh take the shift back (M·T(−d)); their children are kept where
// they were (T(d)·M). Refused where a node's transform is animated or drives a skin: a fixed
// correction would not hold there.
void GltfDocument::shift_nodes(const std::map<std::size_t, Eigen::Vector3d>& shifts, ByteEdits& json_edits) const {
  if (shifts.empty()) return;
  std::set<std::size_t> animated;
  for (const Json& a : json_.value("animations", Json::array()))
    for (const Json& c : a.value("channels", Json::array()))
      if (c.is_object() && c.contains("target") && c["target"].value("path", std::string()) != "weights" &&
          c["target"].contains("node") && c["target"]["node"].is_number_unsigned())
        animated.insert(c["target"]["node"].get<std::size_t>());
  std::map<std::size_t, std::pair<Eigen::Vector3d, Eigen::Vector3d>> correction;  // node → (before, after)
  const auto node_of = [&](std::size_t index) -> const Json& { return item("nodes", index); };
  for (const auto& shift : shifts) {
    const std::size_t mesh = shift.first;
    const Eigen::Vector3d& d = shift.second;
    for (const std::size_t n : mesh_nodes_.at(mesh)) {
      const Json& node = node_of(n);
      const auto refuse = [&](const std::string& why) {
        throw MeshIoError(source_ + ": the marked positions of mesh " + std::to_string(mesh) +
                          " leave the range of its quantized POSITION type, and node " + std::to_string(n) +
                          " cannot take the shift back: " + why);
      };
      if (node.contains("skin")) refuse("it is skinned");
      if (animated.count(n)) refuse("its transform is animated");
      auto& own = correction.try_emplace(n, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).first->second;
      own.second -= d;
      for (const Json& c : node.value("children", Json::array())) {
        const std::size_t child = as_index(c, "a child node");
        if (animated.count(child)) refuse("its child node " + std::to_string(child) + " is animated");
        correction.try_emplace(child, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).first->second.first += d;
      }
    }
  }
  for (const auto& [n, c] : correction) {
    const Json& node = node_of(n);
    const Matrix4 m = node_matrix(node);
    const std::string base = "/nodes/" + std::to_string(n);
    const auto numbers = [](const double* v, int count) {
      std::string text = "[";
      for (int i = 0; i < count; ++i) text += (i ? "," : "") + number_text(v[i]);
      return text + "]";
    };
    if (node.contains("matrix")) {
      Matrix4 shifted = m;
      shifted.col(3).head<3>() += c.first + m.topLeftCorner<3, 3>() * c.second;
      json_edits.replace(spans_->value(base + "/matrix"), numbers(shifted.data(), 16));  // column-major, as glTF
      continue;
    }
    Eigen::Vector3d t = m.col(3).head<3>() + c.first + m.topLeftCorner<3, 3>() * c.second;
    if (spans_->has(base + "/translation")) {
      json_edits.replace(spans_->value(base + "/translation"), numbers(t.data(), 3));
    } else {
      const std::size_t at = spans_->object_start(base);
      json_edits.replace({at, at}, "\"translation\":" + numbers(t.data(), 3) + ",");
    }
  }
}

// NORMAL and TANGENT turned by their vertex's rotation (in world space: normals by the inverse
// transpose of the node's matrix, tangents by the matrix), written back in their own type, as
// long as they were (unit vectors stay unit after quantization), with any bounds they declare.
void GltfDocument::write_directions(const NormalRotations& rotations, std::vector<Buffer>& buffers,
                                    ByteEdits& json_edits) const {
  std::set<std::pair<int, std::size_t>> done;
  std::set<int> turned_accessors;
  for (const Primitive& p : primitives_) {
    if (p.position_source < 0) continue;
    const PositionSource& s = position_sources_[static_cast<std::size_t>(p.position_source)];
    const Eigen::Matrix3d linear = p.world.topLeftCorner<3, 3>();
    const Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    for (const auto& [accessor, is_normal] : {std::pair{p.normal, true}, std::pair{p.tangent, false}}) {
      if (accessor < 0) continue;
      const Layout l = layout_of(static_cast<std::size_t>(accessor));
      for (std::size_t i = 0; i < l.count; ++i) {
        const Eigen::Quaterniond& r = rotations[s.first_slot + i];
        if (r.w() == 1.0 || !done.insert({accessor, i}).second) continue;
        unsigned char* place = element_place(l, i, buffers);
        if (!place) continue;
        const Eigen::Vector4d e = element(l, i, buffers);
        const Eigen::Vector3d local = e.head<3>();
        const double length = local.norm();
        if (!(length > 0)) continue;
        const Eigen::Vector3d world =
            is_normal ? Eigen::Vector3d(normal_matrix * local) : Eigen::Vector3d(linear * local);
        const Eigen::Vector3d turned = r * world;
        Eigen::Vector3d back =
            is_normal ? Eigen::Vector3d(linear.transpose() * turned) : Eigen::Vector3d(linear.inverse() * turned);
        encode_direction(place, l.component_type, l.normalized, back.normalized(), length);
        turned_accessors.insert(accessor);
      }
    }
  }
  for (const int accessor : turned_accessors) {
    const std::string base = "/accessors/" + std::to_string(accessor);
    if (spans_->has(base + "/min") || spans_->has(base + "/max"))
      update_bounds(static_cast<std::size_t>(accessor), buffers, json_edits);
  }
}

// A Draco primitive whose points moved: its stream encoded again. Its view keeps its offset and
// takes the new length (padded to 4 bytes); the views after it in its buffer move by the
// change, their offsets patched, and so does the buffer's length.
void GltfDocument::write_draco(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const {
  std::map<int, std::vector<std::pair<std::size_t, std::string>>> replaced;  // buffer → (view, new bytes)
  for (const DracoSource& d : draco_) {
    Vertices local = d.codec.positions();
    const Matrix4 inverse = d.world.inverse();
    bool changed = false;
    for (Eigen::Index i = 0; i < local.rows(); ++i) {
      const auto slot = static_cast<Eigen::Index>(d.first_slot) + i;
      if (P.row(slot) == positions_.row(slot)) continue;
      local.row(i) = (inverse * P.row(slot).transpose().homogeneous()).head<3>().transpose();
      changed = true;
    }
    if (!changed) continue;
    std::string encoded = d.codec.encode(local);
    const Vertices decoded = DracoPrimitive(encoded, d.position_id).positions();  // the bounds of what readers will see
    Eigen::Vector4d lo = Eigen::Vector4d::Zero(), hi = lo;
    lo.head<3>() = decoded.colwise().minCoeff().transpose();
    hi.head<3>() = decoded.colwise().maxCoeff().transpose();
    set_bounds(d.accessor, lo, hi, 3, kFloat, json_edits);
    replaced[view_of(d.view).buffer].emplace_back(d.view, std::move(encoded));
  }
  for (auto& [buffer, views] : replaced) {
    std::sort(views.begin(), views.end(),
              [&](const auto& a, const auto& b) { return view_of(a.first).offset < view_of(b.first).offset; });
    const std::string& old = buffers[static_cast<std::size_t>(buffer)].bytes;
    std::string rebuilt;
    std::size_t at = 0;
    std::vector<std::pair<std::size_t, long long>> shifts;  // (old end of a replaced view, shift after it)
    for (const auto& [view, bytes] : views) {
      const View v = view_of(view);
      rebuilt.append(old, at, v.offset - at);
      rebuilt.append(bytes);
      rebuilt.append(align4(bytes.size()) - bytes.size(), '\0');
      at = std::min(old.size(), v.offset + align4(v.length));
      shifts.emplace_back(v.offset + v.length, static_cast<long long>(rebuilt.size()) - static_cast<long long>(at));
      set_member("/bufferViews/" + std::to_string(view), "byteLength", bytes.size(), json_edits);
    }
    rebuilt.append(old, at, std::string::npos);
    const Json& all = json_.value("bufferViews", Json::array());
    long long last_view_end = 0;  // after the rewrite
    for (std::size_t view = 0; view < all.size(); ++view) {
      const View v = view_of(view);
      if (v.buffer != buffer) continue;
      long long by = 0;
      for (const auto& [end, shift] : shifts)
        if (v.offset >= end) by = shift;
      const auto own = std::find_if(views.begin(), views.end(), [&](const auto& r) { return r.first == view; });
      const long long length =
          own != views.end() ? static_cast<long long>(own->second.size()) : static_cast<long long>(v.length);
      last_view_end = std::max(last_view_end, static_cast<long long>(v.offset) + by + length);
      if (by != 0)
        set_member("/bufferViews/" + std::to_string(view), "byteOffset",
                   static_cast<std::uint64_t>(static_cast<long long>(v.offset) + by), json_edits);
    }
    // The declared length keeps its distance to the end of the bytes (GLB padding), but always
    // covers every view and never exceeds the bytes.
    const long long declared =
        static_cast<long long>(whole(json_["buffers"][static_cast<std::size_t>(buffer)], "byteLength", 0));
    const long long resized =
        std::clamp(declared + static_cast<long long>(rebuilt.size()) - static_cast<long long>(old.size()),
                   std::min<long long>(std::max<long long>(last_view_end, 1), static_cast<long long>(rebuilt.size())),
                   static_cast<long long>(rebuilt.size()));
    set_member("/buffers/" + std::to_string(buffer), "byteLength", static_cast<std::uint64_t>(resized), json_edits);
    buffers[static_cast<std::size_t>(buffer)].bytes = std::move(rebuilt);
  }
}

DocumentFiles GltfDocument::write(const Vertices& P, const NormalRotations& rotations,
                                  const CompanionNames& names) const {
  if (P.rows() != positions_.rows())
    throw MeshIoError(source_ + ": " + std::to_string(P.rows()) + " positions for " +
                      std::to_string(positions_.rows()) + " slots");
  if (P == positions_ && (rotations.empty() || std::all_of(rotations.begin(), rotations.end(),
                                                           [](const auto& q) { return q.w() == 1.0; }))) {
    return main_file_only(bytes_);
  }
  try {
    if (const std::string problem = aliasing_problem(); !problem.empty()) throw MeshIoError(source_ + ": " + problem);
    std::vector<Buffer> buffers = buffers_;
    ByteEdits json_edits;
    write_positions(P, buffers, json_edits);
    if (!rotations.empty()) write_directions(rotations, buffers, json_edits);
    write_draco(P, buffers, json_edits);
    return assemble(buffers, json_edits, names);
  } catch (const nlohmann::json::exception& e) {  // a member the reader did not need, of the wrong type
    throw MeshIoError(source_ + ": malformed glTF: " + e.what());
  }
}

// The files: the JSON with its edits (and any data URI re-encoded); for a GLB the container
// rebuilt around the new JSON and binary chunks (other chunks kept); external buffers that
// changed, by their URI.
DocumentFiles GltfDocument::assemble(const std::vector<Buffer>& buffers, const ByteEdits& edits,
                                     const CompanionNames& names) const {
  ByteEdits all = edits;
  DocumentFiles files;
  std::string bin;
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (buffers[i].bytes == buffers_[i].bytes) continue;
    switch (buffers[i].origin) {
      case Buffer::Origin::glb_chunk:
        bin = buffers[i].bytes;
        break;
      case Buffer::Origin::file: {
        const std::string uri = names ? names(buffers[i].uri) : buffers[i].uri;
        if (uri != buffers[i].uri)
          all.replace(spans_->value("/buffers/" + std::to_string(i) + "/uri"), Json(uri).dump());
        files[uri] = buffers[i].bytes;
        break;
      }
      case Buffer::Origin::data_uri: {
        const std::string& uri = buffers_[i].uri;
        const std::string prefix = uri.substr(0, uri.find(',') + 1);
        all.replace(spans_->value("/buffers/" + std::to_string(i) + "/uri"),
                    Json(prefix + base64_encode(buffers[i].bytes)).dump());
        break;
      }
    }
  }
  const std::string json = all.empty() ? json_text_ : all.apply(json_text_);
  if (!binary_) {
    files[""] = json;
    return files;
  }
  // GLB: header, JSON chunk (padded with spaces), then the other chunks in order (padded with zeros).
  const auto put32 = [](std::string& out, std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  std::string out(12, '\0');
  std::string padded_json = json;
  padded_json.append(align4(padded_json.size()) - padded_json.size(), ' ');
  put32(out, static_cast<std::uint32_t>(padded_json.size()));
  put32(out, kJsonChunk);
  out += padded_json;
  for (std::size_t c = 1; c < chunks_.size(); ++c) {
    std::string data =
        chunks_[c].type == kBinChunk && !bin.empty() ? bin : bytes_.substr(chunks_[c].offset, chunks_[c].length);
    data.append(align4(data.size()) - data.size(), '\0');
    put32(out, static_cast<std::uint32_t>(data.size()));
    put32(out, chunks_[c].type);
    out += data;
  }
  const std::uint32_t magic = kGlbMagic, version = 2, length = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data(), &magic, 4);
  std::memcpy(out.data() + 4, &version, 4);
  std::memcpy(out.data() + 8, &length, 4);
  files[""] = std::move(out);
  return files;
}

}  // namespace meshmark::gltf
