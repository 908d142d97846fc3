#include "drvslam/core/thread_name.h"

#include <string>

#ifdef __linux__
#include <pthread.h>
#endif

namespace drvslam {

void NameCurrentThread(const char* name) {
#ifdef __linux__
  // pthread_setname_np fails (ERANGE) on more than 15 characters instead of cutting the name.
  const std::string cut = std::string(name).substr(0, 15);
  pthread_setname_np(pthread_self(), cut.c_str());
#else
  (void)name;
#endif
}

}  // namespace drvslam
