// Invariant checks: PTLAB_CHECK always, PTLAB_DCHECK in debug builds only.
#pragma once

#include <cstdio>
#include <cstdlib>

#define PTLAB_CHECK(cond)                                                              \
  do {                                                                                 \
    if (!(cond)) {                                                                     \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);    \
      std::abort();                                                                    \
    }                                                                                  \
  } while (0)

#ifndef NDEBUG
#define PTLAB_DCHECK(cond) PTLAB_CHECK(cond)
#else
#define PTLAB_DCHECK(cond) \
  do {                     \
  } while (0)
#endif
