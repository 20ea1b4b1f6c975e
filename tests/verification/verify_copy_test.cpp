#include "core/verification/verify_copy.hpp"

#include <gtest/gtest.h>

#include "core/io/write_mesh.hpp"
#include "core/verification/read_back.hpp"
#include "tests/test_data.hpp"
#include "tests/watermark/end_to_end_secrets.hpp"

namespace meshmark {
namespace {

struct Subject {
  PreparedModel model = prepare_model(test::procedural_mesh("creature"));
  RegistrationTarget target{model.outward_mesh()};
};

const Subject& subject() {
  static const Subject s;
  return s;
}

TEST(VerifyCopy, AMarkedCopyReadsBackAsWrittenAndAfterTheMildAttack) {
  const Subject& s = subject();
  const EmbedResult marked = embed_watermark(s.model, test::kEndToEndKey, test::end_to_end_payload());
  const Mesh as_written = read_back(write_mesh_to_memory(marked.mesh, MeshFormat::obj), MeshFormat::obj);
  const CopyVerification v =
      verify_copy(s.model, s.target, as_written, test::kEndToEndKey, test::end_to_end_payload(), {});
  ASSERT_EQ(v.readings.size(), 2u);
  EXPECT_EQ(v.readings[0].name, "as written");
  for (const CopyReading& r : v.readings) {
    EXPECT_TRUE(r.passed) << r.name;
    EXPECT_EQ(r.ber, 0.0) << r.name;
    EXPECT_LT(r.log10_p_value, -6) << r.name;
  }
  EXPECT_TRUE(v.passed());
  EXPECT_NO_THROW(require_readable(v, test::end_to_end_payload()));
}

// Once registration has found a moved copy of this model, a copy's re-save is read in place.
TEST(VerifyCopy, WithRegistrationProvenTheResaveIsReadInPlace) {
  const Subject& s = subject();
  const EmbedResult marked = embed_watermark(s.model, test::kEndToEndKey, test::end_to_end_payload());
  VerifyOptions verify;
  verify.registration_proven = true;
  const CopyVerification v =
      verify_copy(s.model, s.target, marked.mesh, test::kEndToEndKey, test::end_to_end_payload(), {}, verify);
  ASSERT_EQ(v.readings.size(), 2u);
  EXPECT_EQ(v.readings[1].name, "re-saved with 6 digits");
  EXPECT_FALSE(v.readings[1].registered);
  EXPECT_TRUE(v.passed());
  const CopyVerification unmarked =
      verify_copy(s.model, s.target, s.model.mesh, test::kEndToEndKey, test::end_to_end_payload(), {}, verify);
  EXPECT_FALSE(unmarked.passed());
}

// A triangle format numbers the vertices by first use when read back: the copy, its faces the
// original's corner for corner, is still read in place, not searched for by registration.
TEST(VerifyCopy, ACopyReadBackFromTrianglesIsReadInPlace) {
  const Subject& s = subject();
  const EmbedResult marked = embed_watermark(s.model, test::kEndToEndKey, test::end_to_end_payload());
  const Mesh as_written =
      read_back(write_mesh_to_memory(marked.mesh, MeshFormat::stl, {.binary = true}), MeshFormat::stl);
  ASSERT_EQ(as_written.V.rows(), s.model.mesh.V.rows());
  ASSERT_NE(as_written.F, s.model.mesh.F) << "the read-back kept the original's numbering: nothing is tested";
  VerifyOptions verify;
  verify.registration_proven = true;
  const CopyVerification v =
      verify_copy(s.model, s.target, as_written, test::kEndToEndKey, test::end_to_end_payload(), {}, verify);
  ASSERT_EQ(v.readings.size(), 2u);
  for (const CopyReading& r : v.readings) {
    EXPECT_FALSE(r.registered) << r.name;
    EXPECT_TRUE(r.passed) << r.name;
  }
  Mesh other_faces = as_written;  // one face turned: no longer the original's corner for corner
  std::swap(other_faces.F(0, 0), other_faces.F(0, 1));
  EXPECT_TRUE(verify_copy(s.model, s.target, other_faces, test::kEndToEndKey, test::end_to_end_payload(), {}, verify)
                  .readings[0]
                  .registered);
}

// A spheroid (a bottle's axes: two principal variances alike) registers by its details, so the
// pose found can depend on the mark: every copy is moved and registered, proven or not.
TEST(VerifyCopy, AShapeWithTurnsToSearchIsRegisteredEveryTime) {
  Mesh spheroid = test::icosphere(4);
  spheroid.V.col(2) *= 1.6;
  const PreparedModel model = prepare_model(spheroid);
  const RegistrationTarget target(model.outward_mesh());
  ASSERT_TRUE(turns_ambiguous(target));
  EXPECT_FALSE(turns_ambiguous(subject().target));
  const EmbedResult marked = embed_watermark(model, test::kEndToEndKey, test::end_to_end_payload());
  VerifyOptions verify;
  verify.registration_proven = true;
  const CopyVerification v =
      verify_copy(model, target, marked.mesh, test::kEndToEndKey, test::end_to_end_payload(), {}, verify);
  ASSERT_EQ(v.readings.size(), 2u);
  EXPECT_TRUE(v.readings[1].registered);
  EXPECT_EQ(v.readings[1].name, "re-saved with 6 digits and moved");
}

TEST(VerifyCopy, AnUnmarkedCopyIsRefusedSayingWhichReadingFailedAndWhatToTry) {
  const Subject& s = subject();
  const CopyVerification v =
      verify_copy(s.model, s.target, s.model.mesh, test::kEndToEndKey, test::end_to_end_payload(), {});
  EXPECT_FALSE(v.passed());
  try {
    require_readable(v, test::end_to_end_payload());
    FAIL() << "an unmarked copy passed";
  } catch (const CopyUnreadable& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("does not read back as written"), std::string::npos) << message;
    EXPECT_NE(message.find("shorter payload"), std::string::npos) << message;
  }
}

TEST(VerifyCopy, ACopyThatReadsAsWrittenButNotMovedIsRefusedSayingWhatMayWork) {
  CopyVerification v;
  v.readings.push_back({.name = "as written", .passed = true, .detected = true, .payload_read = true, .ber = 0});
  v.readings.push_back({.name = "re-saved with 6 digits and moved", .registered = true, .poses = 6});
  try {
    require_readable(v, test::end_to_end_payload());
    FAIL() << "a copy that did not read back moved passed";
  } catch (const CopyUnreadable& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("fits about as well in 6 poses"), std::string::npos) << message;
    EXPECT_NE(message.find("another payload (or a shorter one) may read back"), std::string::npos) << message;
  }
}

TEST(VerifyCopy, AWrongPayloadIsNotAPass) {
  const Subject& s = subject();
  const EmbedResult marked = embed_watermark(s.model, test::kEndToEndKey, test::end_to_end_payload());
  const CopyVerification v =
      verify_copy(s.model, s.target, marked.mesh, test::kEndToEndKey, bits_from_hex("0123456789abcdef"), {});
  EXPECT_FALSE(v.passed());
}

TEST(ReadBack, AMeshWithoutCompanionsReadsBackInItsFormatsPrecision) {
  const Mesh& mesh = test::procedural_mesh("creature_small");
  DocumentFiles files{{"", write_mesh_to_memory(mesh, MeshFormat::off)}};
  bool asked = false;
  const Mesh back = read_back(files, MeshFormat::off, [&](const std::string&) {
    asked = true;
    return std::string();
  });
  EXPECT_FALSE(asked) << "an OFF has no companions";
  EXPECT_EQ(back.V.rows(), mesh.V.rows());
  EXPECT_LT((back.V - mesh.V).cwiseAbs().maxCoeff(), 1e-5);
}

}  // namespace
}  // namespace meshmark
