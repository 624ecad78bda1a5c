/* ncjoule C API: predict the time and energy of a CNC milling program from a post-processor or
 * any other program. C linkage, plain C types only; link with -lncjoule.
 *
 *   ncjoule_context* ctx = ncjoule_context_create("machines/haas.toml");
 *   if (!ctx) { fprintf(stderr, "%s\n", ncjoule_last_error()); return 1; }
 *   ncjoule_context_set_stock(ctx, "box:0,0,-20,100,60,0");
 *   ncjoule_result* r = ncjoule_estimate_file(ctx, "part.ngc");
 *   ncjoule_totals t;
 *   if (r && ncjoule_result_totals(r, &t) == 0) printf("%.1f s, %.1f kJ\n", t.time_s, t.energy_j /
 * 1000); ncjoule_result_destroy(r); ncjoule_context_destroy(ctx);
 *
 * Functions that can fail return NULL or a non-zero int; ncjoule_last_error() then says why (the
 * text belongs to the calling thread and stays valid until its next failing call). Strings the
 * library returns belong to the object they came from, except those documented as freed with
 * ncjoule_free(). A context may be used by one thread at a time; results are read-only. */
#ifndef NCJOULE_H
#define NCJOULE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ncjoule_context ncjoule_context;
typedef struct ncjoule_result ncjoule_result;

/* Program totals. Units: s, J, mm^3, J/mm^3, kg, currency of the profile, W. */
typedef struct ncjoule_totals {
  double time_s;
  double energy_j;
  double removed_mm3;
  double sec_j_mm3; /* energy / removed volume; 0 when nothing is removed */
  double co2_kg;
  double cost;
  double mean_power_w;
  double peak_power_w;
} ncjoule_totals;

/* One source line that holds code, over every time it ran. */
typedef struct ncjoule_block {
  int line;         /* 1-based line in the file */
  const char* kind; /* "rapid", "feed", "arc", "tool_change", "dwell", "setting", ... */
  double start_s;
  double time_s;
  double removed_mm3;
  double mrr_mm3_s; /* mean over the line */
  double power_w;   /* mean over the line */
  double power_peak_w;
  double energy_j;
} ncjoule_block;

/* The library's version, e.g. "0.1.0". */
const char* ncjoule_version(void);

/* Why the last failing call on this thread failed ("" when none has). */
const char* ncjoule_last_error(void);

/* A context holds a machine profile (TOML file) and the options for the next estimates.
 * Returns NULL if the profile cannot be read or is wrong. */
ncjoule_context* ncjoule_context_create(const char* machine_profile_path);
void ncjoule_context_destroy(ncjoule_context* context);

/* Stock for material removal: "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" (mm) or an STL file path;
 * NULL or "" for the bounding box of the cutting moves. Returns 0, or -1 if the text is wrong. */
int ncjoule_context_set_stock(ncjoule_context* context, const char* stock);
/* 1 (default): simulate material removal; 0: estimate time and air-cutting energy only. */
void ncjoule_context_set_removal(ncjoule_context* context, int enabled);
/* Controller dialect ("auto", "linuxcnc", "fanuc", "haas", "grbl", "mach3", "siemens",
 * "heidenhain", "reprap"); NULL or "" to use the profile's, "auto" to detect it from the program
 * whatever the profile says. Returns 0, or -1 for an unknown name. */
int ncjoule_context_set_dialect(ncjoule_context* context, const char* dialect);

/* Progress of the estimates that follow: `callback(fraction, user)` is called now and then, on the
 * calling thread, with the fraction done (0 to 1) of the program being estimated or annotated.
 * NULL for none. */
typedef void (*ncjoule_progress_callback)(double fraction, void* user);
void ncjoule_context_set_progress(ncjoule_context* context, ncjoule_progress_callback callback,
                                  void* user);

/* Tools. Moves cut with the tool their program selects, described (later sources replacing
 * earlier ones for the same number) by a LinuxCNC tool table, the program's CAM header comments,
 * a job file, and the tools added here; moves with no tool selected use the only tool described,
 * else the default tool (the profile's [default_tool] unless set here). A tool nothing describes
 * is not fatal: its moves are timed without material removal, with a warning.
 *
 * A tool as on the command line: "N:TYPE:DIAMETER[:EXTRA[:EXTRA]]" in mm and degrees, TYPE one of
 * flat, ball, bullnose (EXTRA: corner radius), drill (point angle), chamfer (angle, tip diameter);
 * e.g. "1:flat:6", "4:drill:6.8:118". Returns 0, or -1 if the text is wrong. */
int ncjoule_context_add_tool(ncjoule_context* context, const char* tool);
/* Forgets the tools added with ncjoule_context_add_tool and the job file's. */
void ncjoule_context_clear_tools(ncjoule_context* context);
/* The tool of moves that select and describe none, as "TYPE:DIAMETER[...]" (no number), e.g.
 * "flat:6"; NULL or "" for the machine profile's. Returns 0, or -1 if the text is wrong. */
int ncjoule_context_set_default_tool(ncjoule_context* context, const char* tool);
/* A LinuxCNC tool table (.tbl): lengths for G43, and a tool for each entry with a diameter;
 * `inch` is 1 when its values are in inches. NULL or "" for none. Returns 0, or -1 if it cannot
 * be read (ncjoule_last_error() says where). */
int ncjoule_context_set_tool_table(ncjoule_context* context, const char* path, int inch);
/* A job file (TOML: stock and [[tool]] entries, see the README); NULL or "" for none. Its stock
 * replaces the context's, its tools those added before. Returns 0, or -1 if it cannot be read or
 * is wrong (ncjoule_last_error() says where and why). */
int ncjoule_context_set_job(ncjoule_context* context, const char* path);

/* Estimates a program. NULL when it cannot be estimated (unreadable file); warnings and errors
 * about the program are in the result's diagnostics. */
ncjoule_result* ncjoule_estimate_file(ncjoule_context* context, const char* path);
ncjoule_result* ncjoule_estimate_string(ncjoule_context* context, const char* text, size_t length,
                                        const char* name);
void ncjoule_result_destroy(ncjoule_result* result);

int ncjoule_result_totals(const ncjoule_result* result, ncjoule_totals* totals);
size_t ncjoule_result_block_count(const ncjoule_result* result);
/* Fills `block` with block `index` (0 <= index < block_count); returns 0, or -1 out of range. */
int ncjoule_result_block(const ncjoule_result* result, size_t index, ncjoule_block* block);
size_t ncjoule_result_diagnostic_count(const ncjoule_result* result);
/* "file:line:column: warning: message"; NULL out of range. */
const char* ncjoule_result_diagnostic(const ncjoule_result* result, size_t index);
/* The whole result as the JSON document of `ncjoule estimate --json` (docs/json.md). */
const char* ncjoule_result_json(const ncjoule_result* result);

/* Annotates a program held in memory (old annotations are replaced). Returns the annotated text,
 * NUL-terminated, to be freed with ncjoule_free(), and its length in *out_length when not NULL;
 * NULL when the program cannot be estimated (see ncjoule_last_error()). A program with errors its
 * controller would refuse is annotated all the same, its header listing them. */
char* ncjoule_annotate_string(ncjoule_context* context, const char* text, size_t length,
                              const char* name, size_t* out_length);
/* Annotates the file at in_path into out_path (NULL, empty or the same file as in_path: in
 * place). The output is written to a temporary file and renamed into place, so on failure
 * (non-zero return) the target is as it was. Returns 0 on success.
 * In place, the guards of `ncjoule annotate --in-place` hold (docs/annotation.md, "Writing
 * files"): a symbolic link is refused (its target is never rewritten); a file another program
 * still holds open for writing, or that changed while it was read and annotated (checked once
 * the new text is on disk, right before the rename), is refused, as is a program without an end
 * that has not been left alone for 2 seconds. */
int ncjoule_annotate_file(ncjoule_context* context, const char* in_path, const char* out_path);

/* Frees memory the library documents as the caller's. */
void ncjoule_free(void* pointer);

#ifdef __cplusplus
}
#endif

#endif /* NCJOULE_H */
