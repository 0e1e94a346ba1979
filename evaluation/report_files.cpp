#include "evaluation/report_files.hpp"

#include <system_error>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"

namespace owsim {

void write_report_files(const std::filesystem::path& directory, std::span<const ReportFile> files) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw file_error(directory.string(), "cannot create the output folder: " + error.message());
  }
  std::vector<AtomicOutputFile> written;
  written.reserve(files.size());
  for (const ReportFile& file : files) {
    written.emplace_back(directory / file.name);
    written.back().write(file.text);
  }
  // Every byte handed to the kernel, so a full disk shows before the first rename.
  for (AtomicOutputFile& file : written) file.flush();
  // A rename onto a directory fails: found before the first rename, not after it.
  for (const AtomicOutputFile& file : written) {
    if (std::filesystem::is_directory(std::filesystem::symlink_status(file.final_path(), error))) {
      throw file_error(file.final_path().string(),
                       "is a folder: cannot replace it with the report");
    }
  }
  for (AtomicOutputFile& file : written) file.commit();
}

}  // namespace owsim
