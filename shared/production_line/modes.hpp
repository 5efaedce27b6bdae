// shared/production_line/modes.hpp — the generator's two modes behind generate_production_line
// (internal): generated equipment (line_builder.cpp) or given mesh files (file_mode.cpp).
#pragma once

#include "shared/production_line.hpp"

namespace antcd::shared::line {

/// The veneer line: stations of generated equipment. Options are already validated.
GeneratedScene generate_equipment(const ProductionLineOptions& options);

/// The given mesh files in pairs along x. Options are already validated.
GeneratedScene generate_from_files(const ProductionLineOptions& options);

}  // namespace antcd::shared::line
