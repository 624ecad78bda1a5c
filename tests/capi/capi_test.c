/* The C API from C: a context from a machine profile, estimates of a file and of a string,
 * totals that agree with the per-block results, and errors with their text. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ncjoule.h"

static int passed = 0, failed = 0;

#define CHECK(condition, what)                                                                    \
  do {                                                                                            \
    if (condition) {                                                                              \
      ++passed;                                                                                   \
    } else {                                                                                      \
      ++failed;                                                                                   \
      fprintf(stderr, "FAIL %s:%d: %s (%s)\n", __FILE__, __LINE__, what, ncjoule_last_error());   \
    }                                                                                             \
  } while (0)

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
      char* again = ncjoule_annotate_string(ctx, annotated, out_length, "bracket.ngc", &again_length);
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
      remove(copy);
      ncjoule_free(annotated);
    }
  }

  /* A string without tool definitions: refused with removal, estimated without. */
  const char* program = "G21 G90\nT3 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n";
  CHECK(ncjoule_estimate_string(ctx, program, strlen(program), "inline.ngc") == NULL,
        "undefined tool refused");
  CHECK(strstr(ncjoule_last_error(), "T3") != NULL, "the error names the tool");
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
