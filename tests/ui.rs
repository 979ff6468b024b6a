//! One compile-fail case per diagnostic (trybuild): the list of files under `tests/ui/` is
//! the list of errors a user can meet, and each `.stderr` is what they read.

#[test]
fn ui() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/dsl/*.rs");
    cases.compile_fail("tests/ui/struct/*.rs");
    cases.compile_fail("tests/ui/units/*.rs");
    cases.compile_fail("tests/ui/models/*.rs");
}
