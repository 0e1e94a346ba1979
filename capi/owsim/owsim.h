/* owsim — the MilOWS / HELLAS obstacle-warning LiDAR simulator, C ABI (INTERFACE.md "Embedding").
 *
 * A thin shell over the C++ facade (owsim/simulation.hpp): what it returns equals what
 * `owsim run` writes, byte for byte. Link libowsim_c.so: CMake target owsim::owsim_c after
 * find_package(owsim), or `pkg-config --cflags --libs owsim`. Compiles as C99 and as C++.
 *
 *   owsim_simulation* sim = NULL;
 *   owsim_frame* frame = NULL;
 *   if (owsim_simulation_open("corridor.yaml", &sim) != OWSIM_OK) {
 *     fprintf(stderr, "%s\n", owsim_last_error());
 *     return 1;
 *   }
 *   for (int64_t k = 0; k < owsim_simulation_frame_count(sim); ++k) {
 *     if (owsim_simulate_frame(sim, k, &frame) != OWSIM_OK) break;  // reuses `frame`
 *     size_t bytes, count;
 *     const void* words = owsim_frame_words(frame, &bytes);          // as in flight.d64
 *     const owsim_return* returns = owsim_frame_returns(frame, &count);  // points.csv rows
 *   }
 *   owsim_frame_release(frame);
 *   owsim_simulation_release(sim);
 *
 * Errors: every fallible call returns an owsim_status (OWSIM_OK = 0) and, on failure, sets this
 * thread's last error, one line naming the file, line or key and the problem, kept until the next
 * failure on the same thread (owsim_last_error). No C++ exception and no abort crosses the
 * boundary. Calls that return a value instead return a documented "none" (NULL, -1, 0) for a NULL
 * handle and set the last error too.
 *
 * Ownership: owsim_simulation_open* and owsim_simulate_frame* create handles the caller releases
 * (owsim_*_release, which accept NULL). Pointers into a frame (words, returns, pulses, rays) stay
 * valid until that frame is refilled or released; strings from a simulation until it is released.
 *
 * Threading: a simulation may be used from any number of threads at once (each with its own
 * frames); owsim starts no threads of its own, its work runs on TBB's process-wide workers, at
 * most owsim_simulation_options.threads at once per simulation (0: every core). A frame handle is
 * used by one thread at a time. The progress callback of owsim_simulation_run is called from one
 * thread at a time, possibly a worker thread.
 */
#ifndef OWSIM_OWSIM_H
#define OWSIM_OWSIM_H

#include <stddef.h>
#include <stdint.h>

#include "owsim/owsim_version.h"

#if defined(__GNUC__)
#define OWSIM_API __attribute__((visibility("default")))
#else
#define OWSIM_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum owsim_status {
  OWSIM_OK = 0,
  OWSIM_ERROR_ARGUMENT = 1,  /* a NULL pointer, a frame out of range, a bad option */
  OWSIM_ERROR_INPUT = 2,     /* a scenario, trajectory or pose owsim cannot use */
  OWSIM_ERROR_FILE = 3,      /* a file or folder that cannot be opened, read, created or written */
  OWSIM_ERROR_CANCELLED = 4, /* the progress callback asked owsim_simulation_run to stop */
  OWSIM_ERROR_INTERNAL = 5   /* out of memory or a bug in owsim: the handles stay usable */
} owsim_status;

typedef struct owsim_simulation owsim_simulation;
typedef struct owsim_frame owsim_frame;

/* ---- version ---- */

/* "MAJOR.MINOR.PATCH" of the library loaded (the macros in owsim_version.h are the header's). */
OWSIM_API const char* owsim_version(void);
/* MAJOR * 10000 + MINOR * 100 + PATCH of the library loaded, as OWSIM_VERSION_NUMBER. */
OWSIM_API uint32_t owsim_version_number(void);

/* This thread's last error message ("" before the first). Valid until this thread's next call. */
OWSIM_API const char* owsim_last_error(void);

/* ---- opening a scenario ---- */

/* What `owsim run` sets with --threads, --frames, --duration, --seed and --no-noise. Start from
 * owsim_simulation_options_default(): later versions may add fields at the end, told apart by
 * struct_size. */
typedef struct owsim_simulation_options {
  uint32_t struct_size; /* sizeof(owsim_simulation_options) */
  int32_t threads;      /* at most this many threads at once; 0: every core */
  int64_t frames;       /* frames 0..frames-1; 0: the scenario's duration or trajectory */
  double duration_s;    /* seconds of flight instead of frames; 0: unset */
  uint64_t seed;        /* replaces the scenario's seed when override_seed is nonzero */
  int32_t override_seed;
  int32_t no_noise; /* nonzero: range noise (sigma = 0) and receiver noise off */
  /* Co-simulation over terrain: the east/north box {west, south, east, north} (m, local frame)
   * the host may fly in besides the scenario's own flight; all 0: that flight's area only.
   * Read only when struct_size covers it (clients built before it was added keep working). */
  double flight_area_enu_m[4];
} owsim_simulation_options;

OWSIM_API owsim_simulation_options owsim_simulation_options_default(void);

/* A scenario file (YAML). *out receives a new handle on success, NULL on failure. */
OWSIM_API owsim_status owsim_simulation_open(const char* scenario_path, owsim_simulation** out);
/* The same with options (NULL: the defaults). */
OWSIM_API owsim_status owsim_simulation_open_with(const char* scenario_path,
                                                  const owsim_simulation_options* options,
                                                  owsim_simulation** out);
/* Scenario YAML text in memory; `name` (NULL: "scenario.yaml") stands for its file in errors and
 * anchors relative paths. */
OWSIM_API owsim_status owsim_simulation_open_yaml(const char* yaml, const char* name,
                                                  const owsim_simulation_options* options,
                                                  owsim_simulation** out);
OWSIM_API void owsim_simulation_release(owsim_simulation* simulation);

/* ---- what a simulation holds ---- */

/* Frames along the scenario's trajectory; -1 for NULL. */
OWSIM_API int64_t owsim_simulation_frame_count(const owsim_simulation* simulation);
/* Pulses (and so words) per frame; 0 for NULL. */
OWSIM_API int32_t owsim_simulation_pulses_per_frame(const owsim_simulation* simulation);
/* 8 for MilOWS (64-bit words, flight.d64), 4 for HELLAS (flight.hellas); 0 for NULL. */
OWSIM_API int32_t owsim_simulation_word_size(const owsim_simulation* simulation);
/* When frame k's first / last pulse fires, seconds on the trajectory's clock; NaN for NULL or a
 * negative k (owsim_last_error says which). */
OWSIM_API double owsim_simulation_frame_start_s(const owsim_simulation* simulation, int64_t frame);
OWSIM_API double owsim_simulation_frame_end_s(const owsim_simulation* simulation, int64_t frame);
/* Objects a return can belong to (owsim_return.object indexes them); 0 for NULL. */
OWSIM_API uint32_t owsim_simulation_object_count(const owsim_simulation* simulation);
/* The object's id ("<span>/<n>" for a conductor, "terrain" last); NULL when out of range. */
OWSIM_API const char* owsim_simulation_object_id(const owsim_simulation* simulation,
                                                 uint32_t object);

/* ---- frames ---- */

/* One detected return: the points.csv columns, in their order, as numbers. */
typedef struct owsim_return {
  int64_t frame;
  int32_t pulse;         /* index within the frame, 0-based */
  int32_t line;          /* scan line within the frame */
  int32_t fiber;         /* 1..127 */
  int32_t return_number; /* points.csv `return`: 1 or 2 */
  double time_s;         /* pulse time on the trajectory's clock */
  double range_m;        /* after noise */
  uint16_t counter;      /* the range counter the word holds */
  uint8_t surface;       /* points.csv `class`: OWSIM_CLASS_* */
  uint8_t number_of_returns;
  uint32_t object;      /* points.csv `object`: owsim_simulation_object_id(simulation, object);
                           OWSIM_NO_OBJECT for a false return (OWSIM_CLASS_NOISE) */
  double e_m, n_m, u_m; /* local East-North-Up metres from the scenario origin */
  double lat_deg, lon_deg, h_m; /* WGS-84 */
  double energy_rel;            /* received / transmitted energy */
  double incidence_deg;
} owsim_return;

enum {
  OWSIM_CLASS_WIRE = 0,
  OWSIM_CLASS_POLE = 1,
  OWSIM_CLASS_TREE = 2,
  OWSIM_CLASS_GROUND = 3,
  OWSIM_CLASS_BUILDING = 4,
  OWSIM_CLASS_FOG = 5,
  OWSIM_CLASS_NOISE = 6, /* a false return: the receiver's noise crossed the threshold */
  OWSIM_CLASS_UNKNOWN = 255
};

/* owsim_return.object of a return that belongs to no object (a false return). */
#define OWSIM_NO_OBJECT UINT32_C(0xFFFFFFFF)

/* One pulse of the scan pattern (`owsim pattern`'s columns). */
typedef struct owsim_pulse {
  int32_t index; /* within the frame */
  int32_t line;
  int32_t fiber;     /* 1..127 */
  int32_t reference; /* nonzero for the reference fiber: no ray leaves the sensor */
  double time_s;
  double alpha_deg;       /* NaN for the reference fiber */
  double beta_deg;        /* the ray's beta, sawtooth included */
  double mirror_beta_deg; /* what the encoder sees */
  int32_t encoder;        /* MilOWS motor encoder count, i16 as in the word; 0 for HELLAS */
  uint8_t frame_gate, line_gate, mov_dir, reserved;
} owsim_pulse;

/* The central ray of a pulse, local ENU: origin in metres, unit direction. */
typedef struct owsim_ray {
  double origin_e_m, origin_n_m, origin_u_m;
  double dir_e, dir_n, dir_u;
} owsim_ray;

/* Frame `frame` (0 <= frame < frame count) along the scenario's trajectory. *out: NULL → a new
 * frame; a frame from an earlier call → refilled in place (its buffers reused). */
OWSIM_API owsim_status owsim_simulate_frame(owsim_simulation* simulation, int64_t frame,
                                            owsim_frame** out);

/* A pose pushed by a host flight simulator (co-simulation): time on the trajectory's clock,
 * position in the scenario's local ENU frame, attitude in degrees (true heading). */
typedef struct owsim_pose {
  double time_s;
  double e_m, n_m, u_m;
  double roll_deg, pitch_deg, heading_deg;
} owsim_pose;

/* Co-simulation: frame `frame` (any >= 0) flown through `poses` (times increasing, covering the
 * frame's first to last pulse), interpolated as the trajectory module does. */
OWSIM_API owsim_status owsim_simulate_frame_poses(owsim_simulation* simulation, int64_t frame,
                                                  const owsim_pose* poses, size_t pose_count,
                                                  owsim_frame** out);
OWSIM_API void owsim_frame_release(owsim_frame* frame);

/* The frame's index; -1 for NULL. */
OWSIM_API int64_t owsim_frame_index(const owsim_frame* frame);
/* The frame's words exactly as in flight.d64 / flight.hellas (little-endian, HELLAS header word
 * excluded); *byte_count = pulses × word size. NULL (and 0) for NULL. */
OWSIM_API const void* owsim_frame_words(const owsim_frame* frame, size_t* byte_count);
/* Every detected return in firing order: the frame's points.csv rows. */
OWSIM_API const owsim_return* owsim_frame_returns(const owsim_frame* frame, size_t* count);
/* Every pulse in firing order, and its central ray (made when first asked for). */
OWSIM_API const owsim_pulse* owsim_frame_pulses(owsim_frame* frame, size_t* count);
OWSIM_API const owsim_ray* owsim_frame_rays(owsim_frame* frame, size_t* count);

/* ---- the reference obstacle detector (docs/detection.md) ---- */

typedef struct owsim_detector owsim_detector;

/* One warning: a track's report in a frame, detections.csv's row (DETECTION-SPEC §5). */
typedef struct owsim_warning {
  int64_t frame;
  double time_s; /* of the frame's first pulse */
  int64_t track;
  int32_t obstacle_class; /* 1 wire, 2 pole, 3 tree */
  uint32_t points;        /* supporting it in this frame's window (0: held without support) */
  double e_m, n_m, u_m;   /* the track's point nearest to the aircraft, local ENU */
  double range_m;         /* its distance from the aircraft */
  double length_m, width_m, height_m;
} owsim_warning;

/* A detector for the simulation's frames, with the scenario's `detector:` section. It reads the
 * frames' words and the scenario's navigation, never their returns' truth: its warnings are what
 * `owsim run --outputs detections` writes. The simulation must outlive it. */
OWSIM_API owsim_status owsim_detector_create(const owsim_simulation* simulation,
                                             owsim_detector** out);
OWSIM_API void owsim_detector_release(owsim_detector* detector);
/* The warnings after `frame` (frames in order, each once), by track id; *warnings stays valid until
 * the detector's next call. */
OWSIM_API owsim_status owsim_detector_add_frame(owsim_detector* detector, const owsim_frame* frame,
                                                const owsim_warning** warnings, size_t* count);

/* ---- whole runs ---- */

/* Called after every frame; return nonzero to stop the run (OWSIM_ERROR_CANCELLED, no output
 * left behind). */
typedef int (*owsim_progress_fn)(int64_t frames_done, int64_t frames_total, void* user_data);

/* What `owsim run` takes besides the simulation options. Start from
 * owsim_run_options_default(). */
typedef struct owsim_run_options {
  uint32_t struct_size;       /* sizeof(owsim_run_options) */
  const char* out_dir;        /* NULL: out/<scenario name>/ */
  const char* outputs;        /* comma list as `owsim run --outputs`; NULL: all */
  int32_t resume;             /* nonzero: continue from the folder's checkpoint */
  owsim_progress_fn progress; /* may be NULL */
  void* user_data;
} owsim_run_options;

typedef struct owsim_run_report {
  int64_t frames;      /* of the whole flight */
  int64_t first_frame; /* > 0 when the run resumed */
  uint64_t pulses;
  double wall_s;
  double pulses_per_s;
  double realtime_factor;
  int32_t threads;
} owsim_run_report;

OWSIM_API owsim_run_options owsim_run_options_default(void);

/* What `owsim run` does: every frame into the output files. report may be NULL. */
OWSIM_API owsim_status owsim_simulation_run(const owsim_simulation* simulation,
                                            const owsim_run_options* options,
                                            owsim_run_report* report);

/* ---- looking at a flight ---- */

/* What `owsim view` takes. Start from owsim_view_options_default(). */
typedef struct owsim_view_options {
  uint32_t struct_size;       /* sizeof(owsim_view_options) */
  const char* out_file;       /* NULL: <folder>/report.html */
  const char* scenario_path;  /* NULL: no scene objects drawn */
  uint64_t max_points;        /* 3D points the page carries (default 2000000) */
  int32_t max_frames;         /* range images the page carries (default 400) */
} owsim_view_options;

typedef struct owsim_view_report {
  uint64_t bytes; /* of the page */
  uint64_t points_total, points_shown;
  int64_t frames_total, frames_shown;
} owsim_view_report;

OWSIM_API owsim_view_options owsim_view_options_default(void);

/* What `owsim view` does: the folder of a run, a decode or a merge + decode as one self-contained
 * page (report.html). options and report may be NULL. */
OWSIM_API owsim_status owsim_view(const char* folder, const owsim_view_options* options,
                                  owsim_view_report* report);

#ifdef __cplusplus
}
#endif

#endif /* OWSIM_OWSIM_H */
