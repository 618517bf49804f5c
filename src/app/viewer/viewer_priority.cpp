#include "app/viewer/viewer_priority.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace neurocloth {

void yield_to_simulation() {
  // On Linux the nice value belongs to the thread: PRIO_PROCESS with a thread id
  // changes this thread only, not the simulation's.
  const auto thread = static_cast<id_t>(syscall(SYS_gettid));
  setpriority(PRIO_PROCESS, thread, getpriority(PRIO_PROCESS, thread) + 10);
}

}  // namespace neurocloth
