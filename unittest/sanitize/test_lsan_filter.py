"""lsan_filter.py: LAMMPS' own leaks pass, every other report is a finding."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import lsan_filter as L  # noqa: E402

HEAD = "=================================================================\n==lmp==1==ERROR: LeakSanitizer: detected memory leaks\n\n"


def leak(kind, func, n=32):
    return (f"{kind} leak of {n} byte(s) in 1 object(s) allocated from:\n"
            "    #0 0x7f in operator new[](unsigned long) asan_new_delete.cpp:98\n"
            f"    #1 0x7f in {func} ../src/x.cpp:965\n"
            "    #2 0x7f in LAMMPS_NS::Input::execute_command() ../src/input.cpp:780\n\n")


def test_lammps_ifthenelse_passes():
    text = HEAD + leak("Direct", "LAMMPS_NS::Input::ifthenelse()") + \
        leak("Indirect", "LAMMPS_NS::FixEQMeso::FixEQMeso(LAMMPS_NS::LAMMPS*, int, char**)")
    assert L.classify(text) == ("lammps", "LAMMPS_NS::Input::ifthenelse")


def test_package_direct_leak_is_a_finding():
    # a leak of a command run through 'if': its own frames come first
    text = HEAD + leak("Direct", "LAMMPS_NS::Input::ifthenelse()") + \
        leak("Direct", "LAMMPS_NS::FixEQMeso::FixEQMeso(LAMMPS_NS::LAMMPS*, int, char**)")
    kind, detail = L.classify(text)
    assert kind == "finding" and "FixEQMeso" in detail


def test_asan_error_and_ubsan_are_findings():
    assert L.classify("==1==ERROR: AddressSanitizer: heap-buffer-overflow")[0] == "finding"
    assert L.classify("fix.cpp:12:5: runtime error: signed integer overflow")[0] == "finding"
    assert L.classify(HEAD + leak("Indirect", "LAMMPS_NS::Input::ifthenelse()"))[0] == "finding"


def caller_leak(func, caller):
    return ("Direct leak of 8 byte(s) in 1 object(s) allocated from:\n"
            "    #0 0x7f in operator new[](unsigned long) asan_new_delete.cpp:98\n"
            f"    #1 0x7f in {func} ../src/utils.cpp:1357\n"
            f"    #2 0x7f in {caller} ../src/run.cpp:143\n\n")


def test_generic_allocator_counts_only_with_its_lammps_caller():
    strdup = "LAMMPS_NS::utils::strdup(std::string const&)"
    ok = HEAD + caller_leak(strdup, "LAMMPS_NS::Run::command(int, char**)")
    assert L.classify(ok) == ("lammps", "LAMMPS_NS::utils::strdup <- LAMMPS_NS::Run::command")
    bad = HEAD + caller_leak(strdup, "LAMMPS_NS::FixEQContacts::parse(int, char**, Args&)")
    kind, detail = L.classify(bad)
    assert kind == "finding" and "strdup" in detail


def test_new_lammps_sites_after_an_error_pass():
    for func in ("LAMMPS_NS::Run::command(int, char**)", "LAMMPS_NS::PairHybrid::save_special()",
                 "LAMMPS_NS::ReadRestart::check_eof_magic()"):
        assert L.classify(HEAD + leak("Direct", func))[0] == "lammps", func


def test_report_cut_off_at_its_end():
    cut = "Direct leak of 8 byte(s) in 1 object(s) allocated from:\n"
    text = HEAD + leak("Direct", "command_creator<LAMMPS_NS::Run>") + cut
    kind, detail = L.classify(text)
    assert kind == "lammps" and "cut off" in detail
    # a cut block after a package leak does not pass
    text = HEAD + leak("Direct", "LAMMPS_NS::FixEQMeso::FixEQMeso(LAMMPS_NS::LAMMPS*, int, char**)") + cut
    assert L.classify(text)[0] == "finding"
    # a block cut in the middle of the report is not the end of a report
    text = HEAD + cut + leak("Direct", "command_creator<LAMMPS_NS::Run>")
    assert L.classify(text)[0] == "finding"


def test_report_cut_off_before_its_first_leak():
    # the header alone, or a first block cut before its first frame: 'cut',
    # not LAMMPS' own and not a finding
    cut = "Direct leak of 192 byte(s) in 1 object(s) allocated from:\n"
    for text in (HEAD, HEAD + cut):
        kind, detail = L.classify(text)
        assert kind == "cut" and "cut off" in detail, text
    # anything else after the header, or a cut block after an indirect
    # one (LeakSanitizer writes the direct leaks first): a finding
    assert L.classify(HEAD + "something else\n")[0] == "finding"
    assert L.classify(HEAD + leak("Indirect", "LAMMPS_NS::Atom::Atom") + cut)[0] == "finding"
    assert L.classify(HEAD + leak("Indirect", "LAMMPS_NS::Atom::Atom"))[0] == "finding"
    # a whole report (its SUMMARY line) without a direct leak is a finding
    summary = "SUMMARY: AddressSanitizer: 32 byte(s) leaked in 1 allocation(s).\n"
    assert L.classify(HEAD + summary)[0] == "finding"
    assert L.classify(HEAD + leak("Indirect", "LAMMPS_NS::Atom::Atom") + summary)[0] == "finding"
    # a complete package leak before a cut block is a finding
    text = HEAD + leak("Direct", "LAMMPS_NS::FixEQContacts::init()") + cut
    assert L.classify(text)[0] == "finding"
