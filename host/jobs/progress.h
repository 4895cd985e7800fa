// progress.h — a progress bar on a terminal, plain lines otherwise (farm logs).
#pragma once
#include <chrono>
#include <string>

namespace seasim {

class Progress {
 public:
  Progress(int total, bool tty);
  // Called when item `index` (0-based count of items handled so far) starts/ends.
  void start(const std::string& item);
  void finish(const std::string& item, const std::string& outcome);
  void done();

 private:
  void drawBar(const std::string& label);
  int total_;
  int handled_ = 0;
  bool tty_;
  std::chrono::steady_clock::time_point t0_;
};

// True when stderr is a terminal.
bool stderrIsTerminal();

}  // namespace seasim
