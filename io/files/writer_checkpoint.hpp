#pragma once
// Where a streaming output writer stood at a checkpoint of `owsim run` (io/run/run_checkpoint.hpp):
// the bytes of its temporary file, all handed to the kernel, and the records (words, rows,
// points) it had written. A writer resumed from it (the writers' resume()) appends exactly the
// bytes an uninterrupted writer would have appended after that point.
#include <cstdint>

namespace owsim {

struct WriterCheckpoint {
  std::uint64_t file_bytes = 0;
  std::uint64_t records = 0;
  friend bool operator==(const WriterCheckpoint&, const WriterCheckpoint&) = default;
};

}  // namespace owsim
