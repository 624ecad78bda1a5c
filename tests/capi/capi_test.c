/* The C API from C: a context from a machine profile, estimates of a file and of a string,
 * totals that agree with the per-block results, and errors with their text. */
#ifndef _WIN32
#define _POSIX_C_SOURCE 200809L /* symlink() */
#endif
#include <math.h>
#include <stdio.h>
#include <string.h>
#ifndef _WIN32
#include <unistd.h>
#endif

#include "ncjoule.h"

static int passed = 0, failed = 0;

#define CHECK(condition, what)                                                                     \
  do {                                                                                             \
    if (condition) {                                                                               \
      ++passed;                                                                                    \
    } else {                                                                                       \
      ++failed;                                                                                    \
      fprintf(stderr, "FAIL %s:%d: %s (%s)\n", __FILE__, __LINE__, what, ncjoule_last_error());    \
    }                                                                                              \
  } while (0)

/* Progress reports: how many, and the last fraction. */
static int progress_calls = 0;
static double progress_last = -1;
static int progress_ordered = 1;
static void on_progress(double fraction, void* user) {
  (void)user;
  if (fraction < progress_last) progress_ordered = 0;
  progress_last = fraction;
  ++progress_calls;
}

/* The JSON text without white space outside strings, so that tests can look for "key":value. */
static const char* compact(const char* json) {
  static char out[1 << 20];
  size_t n = 0;
  int in_string = 0;
  for (const char* p = json; p && *p && n + 1 < sizeof out; ++p) {
    if (*p == '"' && (p == json || p[-1] != '\\')) in_string = !in_string;
    if (!in_string && (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r')) continue;
    out[n++] = *p;
  }
  out[n] = '\0';
  return out;
}

int main(void) {
  const char* zhou = NCJOULE_SOURCE_DIR "/samples/machines/zhou2017-anziani2025.toml";
  const char* sample = NCJOULE_SOURCE_DIR "/samples/programs/bracket-linuxcnc.ngc";

  CHECK(ncjoule_context_create(NCJOULE_SOURCE_DIR "/no/such/profile.toml") == NULL,
        "a missing profile gives no context");
  CHECK(strstr(ncjoule_last_error(), "profile.toml") != NULL, "the error names the file");

  ncjoule_context* ctx = ncjoule_context_create(zhou);
  CHECK(ctx != NULL, "context from the Zhou profile");
  if (!ctx) return 1;
  CHECK(ncjoule_context_set_stock(ctx, "box:0,0,-20,100,60") != 0, "a box needs six numbers");
  CHECK(ncjoule_context_set_stock(ctx, "box:0,0,-20,100,60,0") == 0, "stock box");
  CHECK(ncjoule_context_set_dialect(ctx, "no-such-dialect") != 0, "unknown dialect refused");

  ncjoule_result* r = ncjoule_estimate_file(ctx, sample);
  CHECK(r != NULL, "estimate of the bracket sample");
  if (r) {
    ncjoule_totals t;
    CHECK(ncjoule_result_totals(r, &t) == 0, "totals");
    CHECK(t.time_s > 60 && t.energy_j > 0 && t.removed_mm3 > 6000, "totals are positive");
    CHECK(fabs(t.sec_j_mm3 - t.energy_j / t.removed_mm3) < 1e-9 * t.sec_j_mm3,
          "SEC is energy over volume");
    double time = 0, energy = 0, removed = 0;
    size_t n = ncjoule_result_block_count(r);
    CHECK(n > 10, "blocks");
    for (size_t i = 0; i < n; ++i) {
      ncjoule_block b;
      if (ncjoule_result_block(r, i, &b) != 0) {
        CHECK(0, "block in range");
        break;
      }
      time += b.time_s;
      energy += b.energy_j;
      removed += b.removed_mm3;
    }
    ncjoule_block out_of_range;
    CHECK(ncjoule_result_block(r, n, &out_of_range) != 0, "block index past the end refused");
    CHECK(fabs(time - t.time_s) < 1e-6 * t.time_s, "block times add up to the total");
    CHECK(fabs(energy - t.energy_j) < 1e-6 * t.energy_j, "block energies add up");
    CHECK(fabs(removed - t.removed_mm3) < 1e-6 * t.removed_mm3, "block volumes add up");
    const char* json = ncjoule_result_json(r);
    CHECK(json && strstr(json, "\"energy_j\"") != NULL, "JSON document");
    ncjoule_result_destroy(r);
  }

  /* Annotation: of a string, and of a file in place. */
  {
    FILE* f = fopen(sample, "rb");
    static char original[1 << 16];
    size_t n = f ? fread(original, 1, sizeof original - 1, f) : 0;
    if (f) fclose(f);
    size_t out_length = 0;
    char* annotated = ncjoule_annotate_string(ctx, original, n, "bracket.ngc", &out_length);
    CHECK(annotated != NULL, "annotate a string");
    if (annotated) {
      CHECK(out_length > n && strstr(annotated, "(NCJ ") != NULL, "annotations were added");
      CHECK(strlen(annotated) == out_length, "length and terminator agree");
      /* Annotating the annotated text again gives the same text. */
      size_t again_length = 0;
      char* again =
          ncjoule_annotate_string(ctx, annotated, out_length, "bracket.ngc", &again_length);
      CHECK(again && again_length == out_length && memcmp(again, annotated, out_length) == 0,
            "annotate is idempotent");
      ncjoule_free(again);
      const char* copy = "capi_annotate_test.ngc";
      FILE* w = fopen(copy, "wb");
      if (w) {
        fwrite(original, 1, n, w);
        fclose(w);
      }
      CHECK(ncjoule_annotate_file(ctx, copy, NULL) == 0, "annotate a file in place");
      FILE* r2 = fopen(copy, "rb");
      static char written[1 << 17];
      size_t m = r2 ? fread(written, 1, sizeof written, r2) : 0;
      if (r2) fclose(r2);
      CHECK(m == out_length && memcmp(written, annotated, m) == 0,
            "the file holds the same annotated text");
      CHECK(ncjoule_annotate_file(ctx, "no/such/file.ngc", NULL) != 0, "missing input refused");
#ifndef _WIN32
      /* In place, the command's guards: a symbolic link's target is never rewritten, and a file
       * still open for writing (here by the caller itself, a post that has not closed it yet)
       * is never replaced. */
      const char* target = "capi_link_target.ngc";
      const char* link = "capi_link.ngc";
      FILE* t = fopen(target, "wb");
      if (t) {
        fwrite(original, 1, n, t);
        fclose(t);
      }
      remove(link);
      CHECK(symlink(target, link) == 0, "a link to a program");
      CHECK(ncjoule_annotate_file(ctx, link, NULL) != 0, "in place on a link: refused");
      CHECK(strstr(ncjoule_last_error(), "symbolic link") != NULL, "... saying it is a link");
      FILE* back = fopen(target, "rb");
      m = back ? fread(written, 1, sizeof written, back) : 0;
      if (back) fclose(back);
      CHECK(m == n && memcmp(written, original, n) == 0, "... the link's target untouched");
      FILE* post = fopen(copy, "wb");
      if (post) {
        fwrite(original, 1, n, post);
        fflush(post);
        CHECK(ncjoule_annotate_file(ctx, copy, NULL) != 0, "in place while still open: refused");
        CHECK(strstr(ncjoule_last_error(), "still being written") != NULL, "... saying why");
        fputs("G0 Z50\n", post);
        fclose(post);
        FILE* r3 = fopen(copy, "rb");
        m = r3 ? fread(written, 1, sizeof written, r3) : 0;
        if (r3) fclose(r3);
        CHECK(m == n + 7 && memcmp(written, original, n) == 0 &&
                  memcmp(written + n, "G0 Z50\n", 7) == 0,
              "... every byte the writer wrote kept");
      }
      remove(link);
      remove(target);
#endif
      remove(copy);
      ncjoule_free(annotated);
    }
  }

  /* Progress: reported in order, ending at 1. */
  ncjoule_context_set_progress(ctx, on_progress, NULL);
  r = ncjoule_estimate_file(ctx, sample);
  CHECK(r != NULL && progress_calls >= 2 && progress_last == 1.0 && progress_ordered,
        "progress reported in order up to 1");
  if (r) ncjoule_result_destroy(r);
  ncjoule_context_set_progress(ctx, NULL, NULL);

  /* A string without tool definitions: estimated, T3 named in a warning and not simulated. */
  const char* program = "G21 G90\nT3 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n";
  r = ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc");
  CHECK(r != NULL, "undefined tool: estimated all the same");
  if (r) {
    int named = 0;
    for (size_t i = 0; i < ncjoule_result_diagnostic_count(r); ++i)
      named |= strstr(ncjoule_result_diagnostic(r, i), "warning: tool T3") != NULL;
    CHECK(named, "a warning names the tool");
    CHECK(strstr(compact(ncjoule_result_json(r)), "\"unsimulated_tools\":[3]") != NULL,
          "the JSON lists T3 as not simulated");
    ncjoule_result_destroy(r);
  }
  /* Every way of giving a tool: added, from a tool table, from a job file, the default. */
  CHECK(ncjoule_context_add_tool(ctx, "3:square:6") != 0, "a bad tool is refused");
  CHECK(ncjoule_context_add_tool(ctx, "3:flat:6") == 0, "a tool is added");
  r = ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc");
  CHECK(r != NULL && strstr(compact(ncjoule_result_json(r)), "\"unsimulated_tools\":[]") != NULL,
        "the added tool describes T3");
  if (r) {
    ncjoule_totals t;
    CHECK(ncjoule_result_totals(r, &t) == 0 && t.removed_mm3 > 0, "T3 removes material");
    ncjoule_result_destroy(r);
  }
  ncjoule_context_clear_tools(ctx);
  {
    const char* table = "capi_tools.tbl";
    FILE* f = fopen(table, "w");
    if (f) {
      fputs("T3 P3 Z20 D8 ;8mm ball end mill\n", f);
      fclose(f);
    }
    CHECK(ncjoule_context_set_tool_table(ctx, "no/such/table.tbl", 0) != 0, "missing table");
    CHECK(ncjoule_context_set_tool_table(ctx, table, 0) == 0, "tool table read");
    r = ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc");
    CHECK(r != NULL &&
              strstr(compact(ncjoule_result_json(r)), "\"shape\":\"ball end mill\"") != NULL,
          "the tool table describes T3 as a ball end mill");
    if (r) ncjoule_result_destroy(r);
    ncjoule_context_set_tool_table(ctx, NULL, 0);
    remove(table);
  }
  {
    const char* job = "capi_job.toml";
    FILE* f = fopen(job, "w");
    if (f) {
      fputs("[[tool]]\nnumber = 3\ntype = \"drill\"\ndiameter_mm = 5\n", f);
      fclose(f);
    }
    CHECK(ncjoule_context_set_job(ctx, "no/such/job.toml") != 0, "missing job file");
    CHECK(ncjoule_context_set_job(ctx, job) == 0, "job file read");
    r = ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc");
    CHECK(r != NULL && strstr(compact(ncjoule_result_json(r)), "\"shape\":\"drill\"") != NULL,
          "the job file describes T3");
    if (r) ncjoule_result_destroy(r);
    ncjoule_context_clear_tools(ctx);
    remove(job);
  }
  {
    const char* no_tool = "G21 G90\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n";
    CHECK(ncjoule_context_set_default_tool(ctx, "ball:4") == 0, "default tool set");
    r = ncjoule_estimate_string(ctx, no_tool, strlen(no_tool), "notool.ngc");
    CHECK(r != NULL && strstr(compact(ncjoule_result_json(r)), "\"diameter_mm\":4,") != NULL,
          "moves with no tool selected cut with the default tool");
    if (r) ncjoule_result_destroy(r);
    ncjoule_context_set_default_tool(ctx, NULL);
  }
  ncjoule_context_set_removal(ctx, 0);
  r = ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc");
  CHECK(r != NULL, "estimate without removal");
  if (r) {
    ncjoule_totals t;
    ncjoule_result_totals(r, &t);
    /* 50 mm at 100 mm/min is at least 30 s; 6 mm plunge 3.6 s. */
    CHECK(t.time_s > 33.6 && t.removed_mm3 == 0, "time without removal");
    ncjoule_result_destroy(r);
  }
  ncjoule_context_destroy(ctx);
  printf("%d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
