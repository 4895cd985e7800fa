// test_hooks.h — fault injection for the farm tests (tests/farm/): a real SIGKILL in the middle of
// a frame, once, driven by an environment variable so the real binary under a real scheduler is
// what gets killed. Does nothing unless the variable is set.
#pragma once
#include <string>

namespace seasim {

// SEASIM_TEST_KILL_MID_ITEM="<item name>:<marker file>": when item `item_name` has written its
// first output file (and not yet its report.json) and the marker file does not exist, creates the
// marker and kills this process with SIGKILL. The marker makes it happen once, so the requeued run
// gets through.
void killMidItemIfAsked(const std::string& item_name);

}  // namespace seasim
