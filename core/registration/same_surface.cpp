#include "core/registration/same_surface.hpp"

#include "core/metrics/compare_meshes.hpp"

namespace meshmark {

SurfaceMatch match_surface(const Mesh& given, const RegistrationTarget& original, const JobControl* control) {
  AlignOptions rigid;
  rigid.non_rigid = false;
  const Alignment a = align_to_original(given, original, rigid, control);
  const Mesh aligned{a.transform.apply_to_rows(given.V), given.F};
  CompareOptions compare;
  compare.samples = 20000;
  compare.threads = threads_of(control);
  SurfaceMatch match;
  match.mrms_relative = compare_meshes(original.mesh, aligned, compare).mrms_relative();
  match.same = match.mrms_relative < kSameSurfaceMrms;
  return match;
}

}  // namespace meshmark
