// libFuzzer target: antcd::Model::from_bytes (the model-file reader, docs/model_file.md) on
// arbitrary bytes, and every query on what it accepts.
//
// Random bytes almost never carry a right checksum, so the first byte of an input chooses: even,
// the rest is taken as a model file whose header's payload size and checksum are rewritten to
// match (so the fuzzer reaches the contents' checks: counts, indices, the tree's shape); odd, the
// rest is read as it is (the header's checks). The seeds in fuzz/corpus/model are '0' followed
// by a small saved model. A loaded model is queried against a shifted copy of itself (collide,
// distance, sweep, the point queries, and penetration when closed). Every antcd::Error is an
// accepted outcome; any other exception, a crash, a sanitizer report, a leak or a hang is a
// finding.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>
#include <antcd/points.hpp>
#include <antcd/sweep.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <span>
#include <vector>

#include "bvh/model_file.hpp"

namespace {

[[noreturn]] void unexpected(const char* what) {
  std::fprintf(stderr, "antcd fuzz_model_file: unexpected exception: %s\n", what);
  std::abort();
}

void query(const antcd::Model& model) {
  const antcd::Transform identity = antcd::Transform::identity();
  const antcd::Transform shifted{antcd::Mat3::Identity(), antcd::Vec3(0.25, 0, 0)};
  (void)antcd::collide(model, identity, model, shifted,
                       {.delta = 0.01, .all_contacts = true, .max_contacts = 64});
  (void)antcd::distance(model, identity, model, shifted);
  (void)antcd::sweep(model, identity, shifted, model, shifted, identity, {.max_iterations = 200});
  const std::vector<antcd::Vec3> points = {antcd::Vec3::Zero(), antcd::Vec3(0.1, 0.2, 0.3)};
  (void)antcd::signed_distance(model, identity, points);
  if (model.is_closed()) {
    (void)antcd::contains(model, identity, points);
    (void)antcd::penetration(model, identity, model, shifted, {.max_evaluations = 4});
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::vector<std::uint8_t> bytes(data + 1, data + size);
  namespace d = antcd::detail;
  if (data[0] % 2 == 0 && bytes.size() >= d::kModelHeaderSize) {
    const std::span<const std::uint8_t> payload = std::span(bytes).subspan(d::kModelHeaderSize);
    d::write_le(bytes.data() + d::kModelPayloadSizeOffset, payload.size(), 8);
    d::write_le(bytes.data() + d::kModelChecksumOffset, d::model_checksum(payload), 8);
  }
  try {
    query(antcd::Model::from_bytes(bytes, "fuzz input"));
  } catch (const antcd::Error&) {
    // A clear refusal: fine.
  } catch (const std::exception& e) {
    unexpected(e.what());
  } catch (...) {
    unexpected("not a std::exception");
  }
  return 0;
}
