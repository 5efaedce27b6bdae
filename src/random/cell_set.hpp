// Private: the set of distinct feature-pair cells a search has decided (tested or hit).
#pragma once

#include <antcd/rng.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace antcd::detail {

/// Set of 64-bit keys (open addressing, linear probing, power-of-two capacity). Memory grows
/// with the number of keys only; growth is amortised (doubling), from 64 slots, so that the many
/// short searches of a scene frame do not clear kilobytes each.
class CellSet {
 public:
  CellSet() { table_.assign(64, kEmpty); }

  /// Inserts `key`; true when it was not present.
  bool insert(std::uint64_t key) {
    if (2 * (size_ + 1) > table_.size()) grow();
    return insert_unchecked(key);
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  bool insert_unchecked(std::uint64_t key) {
    const std::size_t mask = table_.size() - 1;
    std::size_t slot = static_cast<std::size_t>(mix_seed(key)) & mask;
    while (table_[slot] != kEmpty) {
      if (table_[slot] == key) return false;
      slot = (slot + 1) & mask;
    }
    table_[slot] = key;
    ++size_;
    return true;
  }

  void grow() {
    std::vector<std::uint64_t> old(table_.size() * 2, kEmpty);
    old.swap(table_);
    size_ = 0;
    for (const std::uint64_t key : old) {
      if (key != kEmpty) insert_unchecked(key);
    }
  }

  std::vector<std::uint64_t> table_;
  std::size_t size_ = 0;
};

}  // namespace antcd::detail
