/* Built against the installed header and library by tests/package/check-installed.sh:
 * capi_smoke PROFILE PROGRAM estimates the program and prints its totals. */
#include <ncjoule.h>
#include <stdio.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: capi_smoke PROFILE PROGRAM\n");
    return 2;
  }
  printf("libncjoule %s\n", ncjoule_version());
  ncjoule_context* context = ncjoule_context_create(argv[1]);
  if (!context) {
    fprintf(stderr, "%s\n", ncjoule_last_error());
    return 1;
  }
  ncjoule_context_set_removal(context, 0);
  ncjoule_result* result = ncjoule_estimate_file(context, argv[2]);
  ncjoule_totals totals;
  int status = 1;
  if (result && ncjoule_result_totals(result, &totals) == 0 && totals.time_s > 0) {
    printf("%.1f s, %.1f kJ\n", totals.time_s, totals.energy_j / 1000);
    status = 0;
  } else {
    fprintf(stderr, "no estimate: %s\n", ncjoule_last_error());
  }
  ncjoule_result_destroy(result);
  ncjoule_context_destroy(context);
  return status;
}
