#pragma once
// Chooses the parser for a device: the 3Dconnexion family for a known
// vendor:product, the axis-event parser for spacenavd, the descriptor parser
// for any other multi-axis controller.

#include <memory>

#include "sculpt/base/result.h"
#include "sculpt/hal/parsers/report_parser.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal {

/// Errors name the device: "sim:pad (1234:5678): not a multi-axis controller
/// (usage page 1 usage 2)".
Result<std::unique_ptr<ReportParser>> make_parser(const DeviceInfo& info);

}  // namespace sculpt::hal
