#pragma once
// The window's thread gives way to the simulation's. Without a GPU (llvmpipe,
// Xvfb) drawing a frame costs as much CPU as many simulation steps and runs on
// the same cores; the simulation must never wait for the renderer.

namespace neurocloth {

// Lowers the calling thread's scheduling priority (nice +10; allowed without
// privileges). Threads it starts afterwards (the GL driver's) inherit it;
// threads started before keep theirs. Failing to lower it changes nothing else,
// so it is not an error.
void yield_to_simulation();

}  // namespace neurocloth
