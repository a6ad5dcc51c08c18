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
