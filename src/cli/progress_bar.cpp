// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#include "cli/progress_bar.h"

#include "cli/interrupt.h"

#include <unistd.h>

#include <cstdio>

namespace dbrg::cli {
namespace {

const char* stage_name(dbrg_stage stage) {
    switch (stage) {
    case DBRG_STAGE_VALIDATE: return "checking points";
    case DBRG_STAGE_SORT: return "sorting";
    case DBRG_STAGE_DELAUNAY: return "Delaunay";
    case DBRG_STAGE_GROW: return "growing";
    case DBRG_STAGE_FILL_HOLES: return "filling holes";
    case DBRG_STAGE_OUTPUT: return "output";
    case DBRG_STAGE_CLEAN: return "cleaning";
    }
    return "working";
}

} // namespace

ProgressBar::ProgressBar(bool enabled) : drawing_(enabled && isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() { finish(); }

int ProgressBar::callback(void* user, dbrg_stage stage, double fraction) {
    ProgressBar& bar = *static_cast<ProgressBar*>(user);
    if (interrupted()) return 1;  // cancels the call
    if (!bar.drawing_) return 0;
    const int permille = int(fraction * 1000);
    if (int(stage) == bar.last_stage_ && permille / 10 == bar.last_permille_ / 10) return 0;
    bar.last_stage_ = int(stage);
    bar.last_permille_ = permille;
    const int width = 40, filled = permille * width / 1000;
    std::fprintf(stderr, "\r%-16s [", stage_name(stage));
    for (int i = 0; i < width; ++i) std::fputc(i < filled ? '#' : ' ', stderr);
    std::fprintf(stderr, "] %3d%%", permille / 10);
    std::fflush(stderr);
    bar.drawn_ = true;
    return 0;
}

void ProgressBar::finish() {
    if (!drawn_) return;
    std::fprintf(stderr, "\r%70s\r", "");
    std::fflush(stderr);
    drawn_ = false;
    last_stage_ = -1;
}

} // namespace dbrg::cli
