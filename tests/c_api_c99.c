/* The C ABI header compiled as C99 (-std=c99 -pedantic-errors -Werror) into a program that links
 * libowsim_c.so alone: opens the scenario given as argv[1], simulates frame 0 and prints its word
 * bytes and return count. Run by ctest, also under the sanitizer build. */
#include <stdio.h>

#include "owsim/owsim.h"

int main(int argc, char** argv) {
  owsim_simulation* simulation = NULL;
  owsim_frame* frame = NULL;
  size_t bytes = 0;
  size_t returns = 0;
  if (argc != 2) return 2;
  if (owsim_simulation_open(argv[1], &simulation) != OWSIM_OK) {
    fprintf(stderr, "%s\n", owsim_last_error());
    return 1;
  }
  if (owsim_simulate_frame(simulation, 0, &frame) != OWSIM_OK) {
    fprintf(stderr, "%s\n", owsim_last_error());
    owsim_simulation_release(simulation);
    return 1;
  }
  (void)owsim_frame_words(frame, &bytes);
  (void)owsim_frame_returns(frame, &returns);
  printf("owsim %s: frame 0: %lu word bytes, %lu returns\n", owsim_version(), (unsigned long)bytes,
         (unsigned long)returns);
  owsim_frame_release(frame);
  owsim_simulation_release(simulation);
  return bytes > 0 && returns > 0 ? 0 : 1;
}
