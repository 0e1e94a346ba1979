// libowsim_mpi.so: the table of distributed/mpi/mpi_module_abi.hpp over MPI (Debian's OpenMPI),
// on MPI_COMM_WORLD. Thin on purpose: what the operations mean lives in
// distributed/communicator.hpp; this file only calls MPI.
#include <mpi.h>

#include <algorithm>
#include <climits>
#include <ctime>
#include <cstring>
#include <vector>

#include "distributed/mpi/mpi_module_abi.hpp"

namespace {

constexpr std::size_t kMaxPart = std::size_t{1} << 30;  // bytes per MPI call (counts are int)

int init(int* rank, int* size, int* local_size, int* threads_ok) {
  int provided = MPI_THREAD_SINGLE;
  if (int rc = MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided); rc != 0) {
    return rc;
  }
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  MPI_Comm node;
  if (int rc = MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
      rc != 0) {
    return rc;
  }
  MPI_Comm_size(node, local_size);
  MPI_Comm_free(&node);
  *threads_ok = provided >= MPI_THREAD_MULTIPLE ? 1 : 0;
  return 0;
}

int finalize() { return MPI_Finalize(); }

void error_text(int code, char* text, std::size_t size) {
  char message[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(code, message, &length) != 0) length = 0;
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(length), size - 1);
  std::memcpy(text, message, n);
  text[n] = '\0';
}

[[noreturn]] void abort_job(int exit_code) {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  __builtin_unreachable();
}

int barrier() { return MPI_Barrier(MPI_COMM_WORLD); }

int sleeping_barrier(int poll_us) {
  MPI_Request request;
  if (int rc = MPI_Ibarrier(MPI_COMM_WORLD, &request); rc != 0) return rc;
  const timespec pause = {0, static_cast<long>(poll_us) * 1000};
  for (;;) {
    int done = 0;
    if (int rc = MPI_Test(&request, &done, MPI_STATUS_IGNORE); rc != 0) return rc;
    if (done) return 0;
    nanosleep(&pause, nullptr);
  }
}

int exclusive_sum(const std::uint64_t* in, std::uint64_t* out, int count) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int rc = MPI_Exscan(in, out, count, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) std::fill_n(out, count, 0);  // MPI leaves rank 0's result undefined
  return rc;
}

int sum(std::uint64_t* values, int count) {
  return MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
}

int max(std::uint64_t* values, int count) {
  return MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
}

int broadcast(void* data, std::size_t size, int root) {
  auto* bytes = static_cast<char*>(data);
  for (std::size_t done = 0; done < size; done += kMaxPart) {
    const int part = static_cast<int>(std::min(kMaxPart, size - done));
    if (int rc = MPI_Bcast(bytes + done, part, MPI_BYTE, root, MPI_COMM_WORLD); rc != 0) return rc;
  }
  return 0;
}

int gather_sizes(std::uint64_t mine, std::uint64_t* counts, int root) {
  return MPI_Gather(&mine, 1, MPI_UINT64_T, counts, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
}

// The parts of a gather are small (a round's frame summaries): each below 2 GiB in all.
int gather_bytes(const void* mine, std::size_t size, void* out, const std::uint64_t* counts,
                 int root) {
  int rank = 0;
  int processes = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &processes);
  std::vector<int> int_counts;
  std::vector<int> displacements;
  if (rank == root) {
    std::uint64_t at = 0;
    for (int p = 0; p < processes; ++p) {
      if (counts[p] > INT_MAX || at > INT_MAX) return MPI_ERR_COUNT;
      int_counts.push_back(static_cast<int>(counts[p]));
      displacements.push_back(static_cast<int>(at));
      at += counts[p];
    }
  }
  if (size > INT_MAX) return MPI_ERR_COUNT;
  return MPI_Gatherv(mine, static_cast<int>(size), MPI_BYTE, out, int_counts.data(),
                     displacements.data(), MPI_BYTE, root, MPI_COMM_WORLD);
}

int reduce_or(std::uint8_t* bytes, std::size_t size, int root) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (std::size_t done = 0; done < size; done += kMaxPart) {
    const int part = static_cast<int>(std::min(kMaxPart, size - done));
    const int rc = rank == root ? MPI_Reduce(MPI_IN_PLACE, bytes + done, part, MPI_UINT8_T,
                                             MPI_BOR, root, MPI_COMM_WORLD)
                                : MPI_Reduce(bytes + done, nullptr, part, MPI_UINT8_T, MPI_BOR,
                                             root, MPI_COMM_WORLD);
    if (rc != 0) return rc;
  }
  return 0;
}

int file_open(const char* path, void** file) {
  auto* handle = new MPI_File;
  const int rc = MPI_File_open(MPI_COMM_WORLD, path, MPI_MODE_WRONLY, MPI_INFO_NULL, handle);
  if (rc != 0) {
    delete handle;
    return rc;
  }
  MPI_File_set_errhandler(*handle, MPI_ERRORS_RETURN);
  *file = handle;
  return 0;
}

int file_write_at(void* file, std::uint64_t offset, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const char*>(data);
  for (std::size_t begin = 0; begin < size; begin += kMaxPart) {
    const int part = static_cast<int>(std::min(kMaxPart, size - begin));
    MPI_Status status;
    if (int rc = MPI_File_write_at(*static_cast<MPI_File*>(file),
                                       static_cast<MPI_Offset>(offset + begin), bytes + begin,
                                       part, MPI_BYTE, &status);
        rc != 0) {
      return rc;
    }
  }
  return 0;
}

int file_sync(void* file) { return MPI_File_sync(*static_cast<MPI_File*>(file)); }

int file_close(void* file) {
  auto* handle = static_cast<MPI_File*>(file);
  const int rc = MPI_File_close(handle);
  delete handle;
  return rc;
}

int send(int destination, int tag, std::uint64_t value) {
  return MPI_Send(&value, 1, MPI_UINT64_T, destination, tag, MPI_COMM_WORLD);
}

int receive(int source, int tag, std::uint64_t* value) {
  return MPI_Recv(value, 1, MPI_UINT64_T, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

int try_receive(int tag, int* source, std::uint64_t* value, int* received) {
  int waiting = 0;
  MPI_Status status;
  if (int rc = MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &waiting, &status); rc != 0) {
    return rc;
  }
  *received = waiting;
  if (!waiting) return 0;
  *source = status.MPI_SOURCE;
  return MPI_Recv(value, 1, MPI_UINT64_T, status.MPI_SOURCE, tag, MPI_COMM_WORLD,
                  MPI_STATUS_IGNORE);
}

constexpr owsim_mpi_table kTable = {OWSIM_MPI_MODULE_ABI,
                                    init,
                                    finalize,
                                    error_text,
                                    abort_job,
                                    barrier,
                                    sleeping_barrier,
                                    exclusive_sum,
                                    sum,
                                    max,
                                    broadcast,
                                    gather_sizes,
                                    gather_bytes,
                                    reduce_or,
                                    file_open,
                                    file_write_at,
                                    file_sync,
                                    file_close,
                                    send,
                                    receive,
                                    try_receive};

}  // namespace

extern "C" __attribute__((visibility("default"))) const owsim_mpi_table* owsim_mpi_module() {
  return &kTable;
}
