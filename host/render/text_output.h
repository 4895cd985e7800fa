// text_output.h — a text file a pass makes for the frame (a CSV beside the image), published as a
// resource the pass names in its plan entry's `writes`. The renderer hands every one the plan wrote to
// FrameResult::texts and the job writes each into the item's folder under its file name; neither knows
// which pass made it.
#pragma once
#include <string>

namespace seasim {

struct TextOutput {
  std::string file_name;  // a plain name, no folder ("profile.csv")
  std::string text;
};

}  // namespace seasim
