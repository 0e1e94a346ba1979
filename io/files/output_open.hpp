#pragma once
// How owsim opens what it writes, so that nothing already sitting at a name is followed or reused
// (issue 45: a symbolic link planted at `points.csv.partial` in a shared folder made owsim write
// through it into a file outside the folder). Every output file is created by
// create_output_file() (AtomicOutputFile's temporary) and reopened only by open_output_file() (a
// resume, the other processes of a distributed run); the folders owsim names inside an output
// folder (quicklook/, inputs/…, a sweep's members) are made by make_output_subfolder(). A folder
// the user names (--out, the studio's output folder) may itself be a symbolic link: the user's
// choice, followed as before.
//
// Failures throw owsim::FileError "<error_path>: <what> <path>: <reason>", one line.
#include <filesystem>
#include <string_view>

namespace owsim {

// Creates `path` new, for writing: whatever sits at the name is removed first — a file, a symbolic
// or hard link (the name only, never what it points to), a FIFO, a device — and a directory is
// refused; then it is opened O_CREAT|O_EXCL|O_NOFOLLOW (mode 0666 less the umask), so a name
// planted again in between is refused, never written through. Returns the descriptor
// (close-on-exec), the caller's to close.
[[nodiscard]] int create_output_file(const std::filesystem::path& path,
                                     std::string_view error_path);

// What create_output_file() does before it creates: removes whatever sits at `path`, refusing a
// directory. For a caller that makes the name itself (a hard link, link() never follows).
void clear_output_name(const std::filesystem::path& path, std::string_view error_path);

// Opens the file an owsim writer created at `path` with `flags` (O_RDONLY, O_WRONLY or O_RDWR),
// never through what was planted since: it is opened O_NOFOLLOW (and without blocking, so a FIFO
// cannot hang it), then the descriptor must be a regular file with one name, owned by this
// process's user. `what` begins the message ("cannot resume from"). Returns the descriptor
// (close-on-exec, blocking), the caller's to close.
[[nodiscard]] int open_output_file(const std::filesystem::path& path, int flags,
                                   std::string_view error_path, std::string_view what);

// Makes the folder `folder` (its parent exists), or accepts the folder already there — but never
// a symbolic link or anything else at the name: owsim named this folder, so a link there was not
// the user's choice and would send the outputs elsewhere.
void make_output_subfolder(const std::filesystem::path& folder);

// make_output_subfolder for each folder of `relative` (a relative path of folders) under `base`,
// outermost first.
void make_output_subfolders(const std::filesystem::path& base,
                            const std::filesystem::path& relative);

}  // namespace owsim
