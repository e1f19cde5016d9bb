#!/usr/bin/env bash
# The documentation site: installs MkDocs (Debian's package) if it is missing,
# then builds docs/ into build/docs/ with warnings as errors (a broken link or
# a page missing from the navigation stops it). Open build/docs/index.html.
#     bash scripts/docs.sh [SITE_DIR]     (default: build/docs)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v mkdocs >/dev/null 2>&1 || bash scripts/install-deps.sh mkdocs
site=${1:-build/docs}
echo "tumble: building the documentation into $site (mkdocs build --strict)" >&2
mkdocs build --strict --quiet -f mkdocs.yml -d "$site"
echo "tumble: the documentation is in $site/index.html" >&2
