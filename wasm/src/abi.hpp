// wasm/src/abi.hpp — the parts of the package's C ABI (bindings.cpp) that the exports in other
// files of wasm/src share: the checked call wrapper, the output block, the model table and the
// pose block. The calling convention is stated at the top of bindings.cpp.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <cstddef>
#include <exception>
#include <memory>

namespace antcd::wasm {

/// Sets the last error to the message of `e` thrown in `function` (or the out-of-memory message),
/// allocating nothing; returns -1.
int fail_with(const char* function, const std::exception& e);

/// Runs `body` (returning an int), turning a thrown antcd or standard exception into -1 and its
/// message. Hot paths do not throw; only argument errors and exhausted memory do.
template <class F>
int guarded(const char* function, F&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    return fail_with(function, e);
  }
}

/// The output block, grown to at least n doubles (may throw std::bad_alloc).
double* out_resize(std::size_t n);

/// The live model with id `id`; throws ArgumentError naming `what` otherwise.
const std::shared_ptr<Model>& model_ref(int id, const char* what);

/// Pose k of the input block as a rigid Transform; throws ArgumentError naming `what`.
Transform pose_at(int k, const char* function, const char* what);

}  // namespace antcd::wasm
