// test_hooks.h — fault injection for the farm tests (tests/farm/): a real SIGKILL in the middle of
// a frame, once, and an item held until the test releases it, driven by environment variables so the
// real binary under a real scheduler is what gets killed or held. Each does nothing unless its
// variable is set.
#pragma once
#include <string>

namespace seasim {

// SEASIM_TEST_KILL_MID_ITEM="<item name>:<marker file>": when item `item_name` has written its
// first output file (and not yet its report.json) and the marker file does not exist, creates the
// marker and kills this process with SIGKILL. The marker makes it happen once, so the requeued run
// gets through.
void killMidItemIfAsked(const std::string& item_name);

// SEASIM_TEST_HOLD_ITEM="<item name>:<release file>": before item `item_name` writes its first
// output file, waits until the release file exists (at most 100 s, then goes on), so a test can
// observe the item running however fast the machine renders it.
void holdItemIfAsked(const std::string& item_name);

}  // namespace seasim
