/* A C program embedding owsim through libowsim_c.so and pkg-config:
 *   cc -std=c99 frames.c $(pkg-config --cflags --libs owsim) -o frames
 *   ./frames examples/single_span.yaml out.d64
 * simulates every frame of the scenario, writes the words (the same bytes as owsim run's
 * flight.d64) and counts the returns by class. */
#include <owsim/owsim.h>
#include <stdio.h>

int main(int argc, char** argv) {
  static const char* const names[] = {"wire", "pole", "tree", "ground"};
  unsigned long by_class[4] = {0, 0, 0, 0};
  owsim_simulation* sim = NULL;
  owsim_frame* frame = NULL;
  FILE* out = NULL;
  int64_t k = 0;
  int status = 1;
  if (argc != 3) {
    fprintf(stderr, "usage: frames SCENARIO.yaml WORDS_FILE\n");
    return 2;
  }
  if (owsim_simulation_open(argv[1], &sim) != OWSIM_OK) goto fail;
  out = fopen(argv[2], "wb");
  if (out == NULL) goto fail;
  for (k = 0; k < owsim_simulation_frame_count(sim); ++k) {
    size_t bytes = 0, count = 0, i = 0;
    const void* words = NULL;
    const owsim_return* returns = NULL;
    if (owsim_simulate_frame(sim, k, &frame) != OWSIM_OK) goto fail;
    words = owsim_frame_words(frame, &bytes);
    if (fwrite(words, 1, bytes, out) != bytes) goto fail;
    returns = owsim_frame_returns(frame, &count);
    for (i = 0; i < count; ++i) {
      if (returns[i].surface < 4) ++by_class[returns[i].surface];
    }
  }
  printf("owsim %s: %lld frames", owsim_version(), (long long)k);
  for (k = 0; k < 4; ++k) printf(", %lu %s", by_class[k], names[k]);
  printf("\n");
  status = 0;
fail:
  if (status != 0)
    fprintf(stderr, "frames: %s\n", *owsim_last_error() ? owsim_last_error() : "cannot write");
  if (out != NULL && fclose(out) != 0) status = 1;
  owsim_frame_release(frame);
  owsim_simulation_release(sim);
  return status;
}
