// The thread pools of the image libraries heightpack's readers and writers drive.
#pragma once

namespace heightpack {

// Sets the thread count of OpenImageIO and OpenEXR for this process (0 = all cores). Their pools are
// process-wide, so a tool calls this once, before any file is read or written.
void setLibraryThreads(int threads);

}  // namespace heightpack
