// paths.h — where the project's data lives at run time.
#pragma once
#include <string>
#include <vector>

namespace seasim {

// <prefix>/share/seasim beside an installed binary (<prefix>/bin/seasim), found from the running
// executable; "" when this binary is not installed (a build tree).
std::string installedShareDir();

// An installed example (jobs/, scenes/) for a relative path such as "jobs/quickstart.toml":
// <installedShareDir()>/<path> when it exists, else "".
std::string installedExample(const std::string& relative_path);

// The data/ folder (spectra, cameras): $SEASIM_DATA_DIR, else the installed <prefix>/share/seasim/data,
// else <source>/data when it exists, else ./data. Throws RuntimeError when none has cie1931_2deg_cmf.csv.
std::string dataDir();

// The folders a camera sensor name is looked up in, in this order: the scene's spectral.camera_dir
// (absolute; "" for none), $SEASIM_CAMERA_DIR, then the shipped data/cameras. Only BSD-licensed
// curves ship; other measured curves (e.g. the CC BY-NC-SA camspec database) stay in a folder the
// user names.
std::vector<std::string> cameraDirs(const std::string& scene_camera_dir = "");

// <dir>/<name>.csv in the first of cameraDirs() that has it; "" when none does.
std::string cameraFile(const std::string& name, const std::string& scene_camera_dir = "");

// The folder of one on-disk cache (kernel binaries: sub = ""): $SEASIM_CACHE_DIR/<sub>, else
// $XDG_CACHE_HOME/seasim/<sub>, else $HOME/.cache/seasim/<sub>; "" when none of those is set.
std::string cacheDir(const std::string& sub);

// A new private folder "$TMPDIR/<stem>-XXXXXX" (/tmp without TMPDIR), made by mkdtemp; "" when it
// cannot be made (errno says why).
std::string makeTempFolder(const std::string& stem);

// Absolute, lexically normal form of `path` relative to the folder of `anchor_file`.
std::string resolveRelativeTo(const std::string& anchor_file, const std::string& path);

// Why `path` cannot be read as an input file, or "" when it is a regular file: "file not found:
// PATH", or the system's reason when the path itself is unusable (a name over 255 bytes, a file
// where a folder should be). Never throws: a path from a file is user input.
std::string inputFileProblem(const std::string& path);

// Why `dir` cannot be an output folder, or "" when it can: a NUL byte in it, a name part longer
// than the file system allows (255 bytes) or a path over 4095 bytes, something that exists and is
// not a folder (a file, /dev/null), or a nearest existing parent that is not a writable folder.
// Checked before anything renders, so the message names the setting instead of a raw I/O error.
std::string outputDirProblem(const std::string& dir);

}  // namespace seasim
