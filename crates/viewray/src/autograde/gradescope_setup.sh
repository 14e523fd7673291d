#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu).
# AUTOGRADER_ROOT moves /autograder (to try the kit outside Gradescope).
set -euo pipefail
source="${AUTOGRADER_ROOT:-/autograder}/source"
chmod +x "$source/bin/viewray" "$source/run_autograder"
# viewray is one program, carried in this zip: check that it runs on this image.
"$source/bin/viewray" --version

# What the students' programs need, if the image lacks it. For example:
#   apt-get update && apt-get install -y python3 python3-numpy    # Python
#   apt-get update && apt-get install -y g++ make                 # C++
