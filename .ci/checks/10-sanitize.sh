#!/usr/bin/env bash
# The whole C suite again under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
make sanitize
