// The doctest suite of whole-run quality checks over many or large samples: how often a statistic holds over
// dozens of seeds, predicate counts against one thread. tests/meson.build leaves it out under the
// sanitizers, where the code these cases run is covered by the other cases and they would take most of the
// run's time; the release build runs them.
#pragma once

namespace dbrg::test {

constexpr const char* QUALITY_SUITE = "quality";

} // namespace dbrg::test
