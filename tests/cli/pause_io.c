/* A shim the output tests preload (LD_PRELOAD) into ncjoule to stop it at one exact point of a
 * write, so that what another program does right then (append to the file, open it, send a
 * signal, kill it) can be tested without relying on timing:
 *
 *   NCJOULE_PAUSE_AT=fsync|rename   the call to stop in (rename also stops renameat2)
 *   NCJOULE_PAUSE_FLAG=PATH         created when the call is reached; the call goes on once the
 *                                   test has removed it (after 20 s at most)
 *
 * The first such call only; every other call goes straight through. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int paused = 0;

static void pause_here(const char* at) {
  const char* want = getenv("NCJOULE_PAUSE_AT");
  const char* flag = getenv("NCJOULE_PAUSE_FLAG");
  if (paused || !want || !flag || strcmp(want, at) != 0) return;
  paused = 1;
  const int fd = open(flag, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd >= 0) close(fd);
  for (int i = 0; i < 2000 && access(flag, F_OK) == 0; ++i) {
    const struct timespec step = {0, 10 * 1000 * 1000};
    nanosleep(&step, NULL);
  }
}

int fsync(int fd) {
  pause_here("fsync");
  int (*real)(int) = (int (*)(int))dlsym(RTLD_NEXT, "fsync");
  return real(fd);
}

int rename(const char* from, const char* to) {
  pause_here("rename");
  int (*real)(const char*, const char*) =
      (int (*)(const char*, const char*))dlsym(RTLD_NEXT, "rename");
  return real(from, to);
}

int renameat2(int from_dir, const char* from, int to_dir, const char* to, unsigned int flags) {
  pause_here("rename");
  int (*real)(int, const char*, int, const char*, unsigned int) =
      (int (*)(int, const char*, int, const char*, unsigned int))dlsym(RTLD_NEXT, "renameat2");
  return real(from_dir, from, to_dir, to, flags);
}
