#!/usr/bin/env python3
"""Replaces one generated section of a results file, leaving the rest (the prose around it) as
it is: the text between "<!-- BEGIN NAME" and "<!-- END NAME -->", markers included.

    replace_section.py FILE NAME WRITER CONTENT

WRITER is the script named in the begin marker; CONTENT a file holding the section's new text.
A FILE that does not exist yet is made with the section alone; one without the markers is an
error (where the section goes is the prose's choice)."""
import sys

path, name, writer, content = sys.argv[1:]
begin = f"<!-- BEGIN {name}"
end = f"<!-- END {name} -->"
section = (f"{begin} (written by {writer}; edits here are overwritten) -->\n"
           + open(content).read() + end + "\n")
try:
    text = open(path).read()
except FileNotFoundError:
    text = begin + "\n" + end + "\n"
b, e = text.find(begin), text.find(end)
if b < 0 or e < b:
    sys.exit(f"{path} has no {name} markers")
open(path, "w").write(text[:b] + section + text[e + len(end) + 1:])
