// The part of the Aerosmith Table Language the rate-table driver speaks, as an AtlCommandTable
// (hil/codecs/atl_command_table.h): JOG (rate mode, integer deg/s), STO (stop), ACL (acceleration,
// deg/s^2), RAT? (measured rate) and STA? (status word), with the framing `<data>\r\n>\r\n`.
// Copied, with their confidence labels, from the lab's table rig_sim/data/atl_commands.json
// (built from shared/protocols.md §1.2); a test checks both agree. RAT? and STA? are UNKNOWN
// (invented: no rate or status query was seen in any client); correct both files together from
// the Aero 800 ATL manual.
#pragma once

#include "hil/codecs/atl_command_table.h"

namespace adahrs::hil {

/// The client's command table (built once).
const AtlCommandTable& AtlClientCommandTable();

}  // namespace adahrs::hil
