#pragma once
// The temporary files of this process (docs/hardening.md): every writer names its temporary
// `<path>.tmp.<pid>` and registers it here while it exists, and a SIGINT or SIGTERM removes
// every registered temporary before the process dies with that signal. A killed run (SIGKILL
// cannot be caught) leaves at most its own `.tmp.<pid>` files, never a damaged output: outputs
// only ever appear by rename.
#include <string>
#include <utility>
#include <vector>

namespace powderbed::bed {

// "<path>.tmp.<pid>": the one temporary name of `path` for this process.
std::string temp_path_for(const std::string& path);

// Registers `temp` for removal on SIGINT/SIGTERM (installing the handlers on first use; a
// handler the program installed itself is left in place and not chained). Async-signal-safe
// bookkeeping: a fixed table of 64 slots, paths up to 4095 bytes; a temporary that does not
// fit is simply not registered (it is still removed by its owner's destructor).
void register_temp_file(const std::string& temp);
// Forgets `temp` (after it was renamed into place or removed).
void unregister_temp_file(const std::string& temp);
// Removes `<path>.tmp.<pid>` files left by processes that no longer exist on this machine (a run
// killed by SIGKILL cannot clean up after itself; the next writer of the same path does). A
// temporary of a live process is never touched. Returns how many were removed.
int remove_stale_temp_files(const std::string& path);
// The same for every `*.tmp.<pid>` file of `folder` (a build's folder left by a killed run).
int remove_stale_temp_files_in(const std::string& folder);
// The handlers' work, callable directly (tests): removes every registered temporary.
void remove_temp_files();

// RAII: registers on construction, on destruction removes the file unless released, and
// unregisters it.
class TempFile {
 public:
  explicit TempFile(std::string temp);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }
  // The file was renamed into place: keep it, forget it.
  void release();

 private:
  std::string path_;
  bool released_ = false;
};

// The outputs of one run, replaced together: while a CommitTogether lives on this thread, every
// atomic writer (write_bed_h5, H5Output, write_text_file, the CSV and deck writers) leaves its
// finished temporary in place instead of renaming it; commit() renames them all, in the order
// written, once every one of them was written. Without commit() (a full disk on the second
// file) the destructor removes them, so no old output of the run was replaced.
class CommitTogether {
 public:
  CommitTogether();
  ~CommitTogether();
  CommitTogether(const CommitTogether&) = delete;
  CommitTogether& operator=(const CommitTogether&) = delete;
  // Renames every waiting temporary over its path; throws InputError naming the path on failure.
  void commit();
  // The one alive on this thread, or nullptr (for the writers).
  static CommitTogether* active();
  // A writer's finished temporary `temp` of `path` (still registered for SIGINT/SIGTERM); a
  // temporary already waiting (the same file written again) waits once, with its latest text.
  void add(std::string temp, std::string path);

 private:
  std::vector<std::pair<std::string, std::string>> waiting_;  // temporary, path
  CommitTogether* outer_;
};

}  // namespace powderbed::bed
