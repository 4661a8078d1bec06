#include "cli/interrupt.h"

#include <csignal>

namespace dbrg::cli {
namespace {

volatile std::sig_atomic_t received_signal = 0;

extern "C" void note_signal(int number) { received_signal = number; }

} // namespace

void watch_interrupts() {
    struct sigaction action = {};
    action.sa_handler = note_signal;
    sigemptyset(&action.sa_mask);
    // The default action comes back after the first signal: a second one stops the program there and then.
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

bool interrupted() { return received_signal != 0; }

int interrupted_exit_code() { return 128 + received_signal; }

} // namespace dbrg::cli
