// python/src/model_guard.cpp — see model_guard.hpp.
#include "model_guard.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <functional>
#include <mutex>
#include <unordered_map>

namespace antcd::python {

namespace {

constexpr std::size_t kStripes = 64;  // one bit each in ModelReadLock::stripes_

/// A reader/writer lock that lets a waiting writer in: readers pass the gate before they take
/// their shared lock, and a writer holds the gate while it waits for the readers in flight, so
/// readers arriving meanwhile wait behind it. (std::shared_mutex alone, on glibc, prefers readers:
/// two threads querying in turn could keep set_vertices out indefinitely.)
struct Stripe {
  std::mutex gate;
  std::shared_mutex rw;
};

std::array<Stripe, kStripes>& stripes() {
  // Leaked on purpose: a daemon thread may still hold a guard while the interpreter exits.
  static auto* const table = new std::array<Stripe, kStripes>();
  return *table;
}

std::size_t stripe_of(const Model& model) {
  // Models are heap objects of some hundred bytes: the low bits of the address carry little.
  const auto address = reinterpret_cast<std::uintptr_t>(&model);
  return std::hash<std::uintptr_t>{}(address >> 4) % kStripes;
}

void lock_shared(std::uint64_t mask) {
  for (std::uint64_t m = mask; m != 0; m &= m - 1) {
    Stripe& s = stripes()[static_cast<std::size_t>(std::countr_zero(m))];
    const std::scoped_lock pass(s.gate);
    s.rw.lock_shared();
  }
}

struct Pins {
  std::mutex mutex;
  std::unordered_map<const Model*, std::size_t> count;
};

Pins& pins() {
  static auto* const table = new Pins();
  return *table;
}

}  // namespace

ModelReadLock::ModelReadLock(const Model& a) : stripes_(std::uint64_t{1} << stripe_of(a)) {
  lock_shared(stripes_);
}

ModelReadLock::ModelReadLock(const Model& a, const Model& b)
    : stripes_((std::uint64_t{1} << stripe_of(a)) | (std::uint64_t{1} << stripe_of(b))) {
  lock_shared(stripes_);  // ascending stripe order
}

ModelReadLock::~ModelReadLock() {
  for (std::uint64_t m = stripes_; m != 0; m &= m - 1) {
    stripes()[static_cast<std::size_t>(std::countr_zero(m))].rw.unlock_shared();
  }
}

ModelWriteLock::ModelWriteLock(const Model& model) : mutex_(stripes()[stripe_of(model)].rw) {
  const std::scoped_lock hold(stripes()[stripe_of(model)].gate);  // while the readers drain
  mutex_.lock();
}

ModelWriteLock::~ModelWriteLock() { mutex_.unlock(); }

void pin_model(const Model& model) {
  Pins& p = pins();
  const std::scoped_lock lock(p.mutex);
  ++p.count[&model];
}

void unpin_model(const Model& model) {
  Pins& p = pins();
  const std::scoped_lock lock(p.mutex);
  const auto it = p.count.find(&model);
  if (it != p.count.end() && --it->second == 0) p.count.erase(it);
}

bool model_pinned(const Model& model) {
  Pins& p = pins();
  const std::scoped_lock lock(p.mutex);
  return p.count.contains(&model);
}

}  // namespace antcd::python
