// The yardstick of bench_process_start: a plain C++ program (libstdc++, iostream) that prints a
// line and exits, so owsim's process start is compared with what any C++ program pays here.
#include <iostream>

int main() {
  std::cout << "plain C++ program\n";
  return 0;
}
