#!/usr/bin/env python3
"""Fails when an option a program's --help mentions is missing from its man pages.

Usage: check_man_pages.py PROGRAM PAGE.1[.gz]... [--without OPTION]

The helps read are the program's --help and `PROGRAM WORD --help` for every subcommand WORD its
help names (a "Commands:" list or "PROGRAM WORD" in a usage line) whose help differs from the
program's; found independently of the pages' generation (man_pages.cmake), so a subcommand that
the generation does not cover fails here. --without OPTION drops OPTION from the pages first:
the test that proves a missing option fails the check.
"""
import gzip
import os
import re
import subprocess
import sys

LONG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
SHORT = re.compile(r"^\s+(-[a-zA-Z0-9]) \[ --", re.M)  # Boost: "  -h [ --help ]"
ANY_SHORT = re.compile(r"(?<![\w-])-[a-zA-Z0-9](?![\w-])")  # where a page may put one


def run_help(program, *words):
    done = subprocess.run([program, *words, "--help"], capture_output=True, text=True,
                          timeout=30)
    return done.stdout if done.returncode == 0 else None


def subcommands(program, text):
    name = re.escape(os.path.basename(program))
    words = set(re.findall(rf"^\s*(?:usage:\s*)?{name} ([a-z][a-z-]*)", text, re.M))
    commands = re.search(r"^Commands:\n((?:  .*\n)+)", text, re.M)
    if commands:
        words |= set(re.findall(r"^  ([a-z][a-z-]*)", commands.group(1), re.M))
    return sorted(words)


def options(text):
    return set(LONG.findall(text)) | set(SHORT.findall(text))


def page_text(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", encoding="utf-8") as f:
        roff = f.read()
    roff = re.sub(r"\\f(\[[^]]*\]|\(..|.)", "", roff)  # font changes
    roff = re.sub(r"\\[,/&]", "", roff)  # italic corrections, zero-width
    return roff.replace("\\-", "-")


def main(argv):
    without = None
    if "--without" in argv:
        i = argv.index("--without")
        without = argv[i + 1]
        del argv[i:i + 2]
    program, pages = argv[0], argv[1:]
    main_help = run_help(program)
    if main_help is None:
        print(f"check_man_pages: {program} --help failed")
        return 1
    helps = {"": main_help}
    for word in subcommands(program, main_help):
        text = run_help(program, word)
        if text is not None and text != main_help:
            helps[word] = text
    text = "\n".join(page_text(p) for p in pages)
    if without:
        text = re.sub(rf"(?<![\w-]){re.escape(without)}(?![\w-])", "", text)
    in_pages = set(LONG.findall(text)) | set(ANY_SHORT.findall(text))
    name = os.path.basename(program)
    missing = 0
    for word, help_text in helps.items():
        for option in sorted(options(help_text) - in_pages):
            print(f"{name}{' ' + word if word else ''}: {option} is in --help but not in "
                  f"{', '.join(os.path.basename(p) for p in pages)}")
            missing += 1
    count = len(set().union(*(options(h) for h in helps.values())))
    subs = ", ".join(w for w in helps if w)
    print(f"check_man_pages: {name}{' (and ' + subs + ')' if subs else ''}: {count} options, "
          f"{missing} missing from the man pages")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
