#!/usr/bin/env bash
# Installs what is missing and builds the package (Release unless BUILD_TYPE says otherwise).
set -euo pipefail
source "$(dirname "$0")/../lib/common.sh"
build_package "$@"
