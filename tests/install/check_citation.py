#!/usr/bin/env python3
"""The license and the citation say the same thing as the build: LICENSE is
the BSD-3-Clause text of "The impactkit developers"; CITATION.cff (CFF 1.2.0)
names that license, the version CMake's project() declares, and the authors
as one entity; the Python module's metadata template names the same license.

    check_citation.py SOURCE_DIR PROJECT_VERSION
"""
import re
import sys
from pathlib import Path

import yaml

source, version = Path(sys.argv[1]), sys.argv[2]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


license_text = (source / "LICENSE").read_text()
check(license_text.startswith("BSD 3-Clause License\n"), "LICENSE is not the BSD 3-Clause text")
check(re.search(r"^Copyright \(c\) 2026, The impactkit developers$", license_text, re.M),
      "LICENSE: no 'Copyright (c) 2026, The impactkit developers' line")
for clause in ("Redistributions of source code must retain",
               "Redistributions in binary form must reproduce",
               "Neither the name of the copyright holder"):
    check(clause in license_text, f"LICENSE lacks the clause '{clause} ...'")

cff = yaml.safe_load((source / "CITATION.cff").read_text())
check(cff.get("cff-version") == "1.2.0", f"cff-version {cff.get('cff-version')!r}, want '1.2.0'")
check(bool(cff.get("title")), "CITATION.cff has no title")
check(bool(cff.get("message")), "CITATION.cff has no message")
check(str(cff.get("version")) == version,
      f"CITATION.cff version {cff.get('version')!r}, CMakeLists.txt's project() {version}")
check(cff.get("license") == "BSD-3-Clause", f"CITATION.cff license {cff.get('license')!r}")
check(cff.get("authors") == [{"name": "The impactkit developers"}],
      f"CITATION.cff authors {cff.get('authors')!r}, want the entity 'The impactkit developers'")

metadata = (source / "python" / "metadata" / "METADATA.in").read_text()
check(re.search(r"^License-Expression: BSD-3-Clause$", metadata, re.M),
      "the Python metadata does not name BSD-3-Clause")

for failure in failures:
    print(f"FAIL: {failure}", file=sys.stderr)
sys.exit(1 if failures else 0)
