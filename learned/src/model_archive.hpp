// Checks of a learned-model file (a PyTorch zip archive) before libtorch reads it.
//
// libtorch's archive reader does not check the zip's CRCs, and its parsers of the archive's
// pickles and TorchScript code throw exceptions of several kinds (some outside c10::Error) on
// damaged input. A model file is therefore read by libtorch only after this check has walked the
// whole zip structure with bounds checks and verified every entry's CRC-32: a truncated,
// bit-flipped or foreign file is refused here with a clear message.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace antcd::learned::detail {

/// The largest model file read, and the most bytes its entries may unpack to (a box-lstm model is
/// some 100 kB).
inline constexpr std::size_t kMaxModelBytes = std::size_t{256} << 20;

/// "" when `bytes` is a zip archive whose structure is consistent (end record, central
/// directory, local headers, all inside the file; stored or deflated entries; no zip64, no
/// encryption) and whose every entry unpacks to its recorded size and CRC-32, within
/// kMaxModelBytes in all; otherwise the problem, one line. Time linear in the unpacked size.
std::string model_archive_problem(std::string_view bytes);

}  // namespace antcd::learned::detail
