// Test shim, loaded with LD_PRELOAD into a tool: the process kills itself
// (SIGKILL) right after its Nth successful SQLite COMMIT, N from the
// environment variable GLOBE_TEST_KILL_AFTER_COMMIT. A kill anywhere between
// two commits leaves the files as they were at the first of them, so running
// a build once per N visits every state an interrupted build can leave
// (robustness_test.cpp). Unset or 0: the shim only passes calls through.
#include <dlfcn.h>
#include <signal.h>
#include <sqlite3.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

extern "C" int sqlite3_exec(sqlite3* db, const char* sql,
                            int (*callback)(void*, int, char**, char**), void* arg, char** errmsg) {
  using Exec = int (*)(sqlite3*, const char*, int (*)(void*, int, char**, char**), void*, char**);
  static const auto real = reinterpret_cast<Exec>(::dlsym(RTLD_NEXT, "sqlite3_exec"));
  static const long target = [] {
    const char* v = std::getenv("GLOBE_TEST_KILL_AFTER_COMMIT");
    return v ? std::atol(v) : 0L;
  }();
  static std::atomic<long> commits{0};
  const int rc = real(db, sql, callback, arg, errmsg);
  if (target > 0 && rc == SQLITE_OK && sql && std::strstr(sql, "COMMIT") && ++commits == target)
    ::raise(SIGKILL);
  return rc;
}
