#pragma once
// The C entry point of libowsim_mpi.so (distributed/mpi/mpi_module.cpp), the optional module that
// holds owsim's one use of MPI: a table of the few operations a distributed run and a sweep need
// (distributed/communicator.hpp). Loaded only by a process that mpirun started, so a process
// that never runs distributed never maps libmpi and its dependencies. The loader
// (distributed/mpi_communicator.cpp) refuses a table whose abi differs from OWSIM_MPI_MODULE_ABI.
// Every function returns 0 on success, or an MPI error code whose text owsim_mpi_error_text gives.
#include <cstddef>
#include <cstdint>

#define OWSIM_MPI_MODULE_ABI 2

extern "C" {
struct owsim_mpi_table {
  int abi;
  // MPI_Init_thread (MPI_THREAD_MULTIPLE wanted: a sweep's hand-out thread beside the workers);
  // `threads_ok` says whether that level was granted.
  int (*init)(int* rank, int* size, int* local_size, int* threads_ok);
  int (*finalize)(void);
  void (*error_text)(int code, char* text, std::size_t size);
  [[noreturn]] void (*abort)(int exit_code);
  int (*barrier)(void);
  // A barrier that sleeps `poll_us` microseconds between tests instead of spinning.
  int (*sleeping_barrier)(int poll_us);
  // Over the uint64 values of every process: the exclusive prefix sums, the sums, the maxima.
  int (*exclusive_sum)(const std::uint64_t* in, std::uint64_t* out, int count);
  int (*sum)(std::uint64_t* values, int count);
  int (*max)(std::uint64_t* values, int count);
  int (*broadcast)(void* data, std::size_t size, int root);
  // `counts` (size processes) at root only; `out` at root holds the parts in rank order.
  int (*gather_sizes)(std::uint64_t mine, std::uint64_t* counts, int root);
  int (*gather_bytes)(const void* mine, std::size_t size, void* out, const std::uint64_t* counts,
                      int root);
  int (*reduce_or)(std::uint8_t* bytes, std::size_t size, int root);  // in place at root
  // One file of every process (opened, synced and closed collectively), each process writing its
  // own bytes at explicit offsets.
  int (*file_open)(const char* path, void** file);
  int (*file_write_at)(void* file, std::uint64_t offset, const void* data, std::size_t size);
  int (*file_sync)(void* file);
  int (*file_close)(void* file);
  // Point to point, one uint64 with a tag; try_receive returns 0 with *received = 0 when nothing
  // is waiting.
  int (*send)(int destination, int tag, std::uint64_t value);
  int (*receive)(int source, int tag, std::uint64_t* value);
  int (*try_receive)(int tag, int* source, std::uint64_t* value, int* received);
};
typedef const owsim_mpi_table* (*owsim_mpi_module_fn)(void);
}
