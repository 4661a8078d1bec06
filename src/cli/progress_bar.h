// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include "dbrg/dbrg.h"

namespace dbrg::cli {

class ProgressBar {
public:
    // enabled: draw at all (false for --quiet); a bar is drawn only when stderr is also a terminal.
    explicit ProgressBar(bool enabled);
    ~ProgressBar();

    // A dbrg_progress_fn: pass the ProgressBar as the user pointer. Cancels once a signal asked the
    // program to stop (interrupt.h).
    static int callback(void* user, dbrg_stage stage, double fraction);

    // Clears the line; later reports draw again.
    void finish();

private:
    bool drawing_;
    bool drawn_ = false;
    int last_permille_ = -1;
    int last_stage_ = -1;
};

} // namespace dbrg::cli
