// Ctrl-C (SIGINT) and SIGTERM as a request to stop: the running call is cancelled through its progress
// callback, so that it removes its temporary files and leaves the old output; a second signal ends the
// program at once.
#pragma once

namespace dbrg::cli {

// Installs the handlers; call once, before any work.
void watch_interrupts();

// Whether a signal asked the program to stop.
bool interrupted();

// The exit status of a program stopped by that signal: 128 + its number, as shells report a killed one.
int interrupted_exit_code();

} // namespace dbrg::cli
