// The doctest runner shared by every test program. A program whose every test case that ran found no
// shared data (support/shared_data.h) exits with 77, which meson reports as a skipped test instead of a pass.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "support/shared_data.h"

namespace {

// meson's exit code for "skipped".
constexpr int EXIT_SKIPPED = 77;

unsigned cases_run = 0;
unsigned cases_without_data = 0;

// Counts the test cases that start; reports nothing.
struct CaseCounter : doctest::IReporter {
    explicit CaseCounter(const doctest::ContextOptions&) {}
    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats&) override {}
    void test_case_start(const doctest::TestCaseData&) override { ++cases_run; }
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats&) override {}
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};

} // namespace

DOCTEST_REGISTER_LISTENER("case_counter", 0, CaseCounter);

void dbrg::test::skip_for_missing_data() { ++cases_without_data; }

int main(int argc, char** argv) {
    doctest::Context context(argc, argv);
    const int failures = context.run();
    if (context.shouldExit() || failures != 0) return failures;
    return cases_run > 0 && cases_without_data == cases_run ? EXIT_SKIPPED : 0;
}
