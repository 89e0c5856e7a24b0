#!/usr/bin/env bash
# Downloads the real models of docs/design.md §7 — Debian's libcgal-demo data (data/meshes/*.off: fandisk,
# bunny00, armadillo, knot, elephant-with-holes, blade, ...; data/points_3/*) — into the dtsl data cache:
#
#   ${DTSL_DATA_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/dtsl}/cgal-demo/data/{meshes,points_3}
#
# the folder framework/datasets reads (data_cache_dir()). Needs no root: `apt-get download` fetches the
# .deb into a temporary folder and `dpkg-deb -x` unpacks it there; nothing is installed. Idempotent: a
# complete cache is left alone (--force downloads again). The cache appears complete or not at all
# (unpacked beside it, then renamed into place).
#
# Usage: scripts/fetch_data.sh [--force]
# Environment: DTSL_DATA_DIR (cache folder); DTSL_CGAL_DEMO_DEB (use this local libcgal-demo .deb
# instead of downloading, e.g. on a machine without network).
set -euo pipefail

die() {
  echo "fetch_data.sh: error: $*" >&2
  exit 1
}

force=0
for arg in "$@"; do
  case "$arg" in
    --force) force=1 ;;
    -h | --help)
      sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *) die "unknown argument '$arg' (usage: scripts/fetch_data.sh [--force])" ;;
  esac
done

if [ -z "${DTSL_DATA_DIR:-}" ] && [ -z "${XDG_CACHE_HOME:-}" ] && [ -z "${HOME:-}" ]; then
  die "neither DTSL_DATA_DIR, XDG_CACHE_HOME nor HOME is set: set DTSL_DATA_DIR to the cache folder"
fi
cache="${DTSL_DATA_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/dtsl}"
dest="$cache/cgal-demo"
marker="$dest/.complete"  # written last: its presence means the extraction finished

if [ "$force" = 0 ] && [ -f "$marker" ] && [ -d "$dest/data/meshes" ] && [ -d "$dest/data/points_3" ]; then
  echo "libcgal-demo data already in $dest ($(cat "$marker")); --force to fetch again"
  exit 0
fi

for tool in dpkg-deb tar; do
  command -v "$tool" > /dev/null || die "'$tool' not found: this script needs a Debian-based system (dpkg, tar)"
done

mkdir -p "$cache" || die "cannot create the cache folder $cache (set DTSL_DATA_DIR to a writable folder)"
[ -w "$cache" ] || die "the cache folder $cache is not writable (set DTSL_DATA_DIR to a writable folder)"

# Everything happens in a temporary folder inside the cache (same file system, so the final rename is
# atomic), removed on any exit.
work="$(mktemp -d "$cache/.cgal-demo.tmp.XXXXXX")"
trap 'rm -rf "$work"' EXIT

if [ -n "${DTSL_CGAL_DEMO_DEB:-}" ]; then
  [ -f "$DTSL_CGAL_DEMO_DEB" ] || die "DTSL_CGAL_DEMO_DEB=$DTSL_CGAL_DEMO_DEB is not a file"
  deb="$DTSL_CGAL_DEMO_DEB"
  echo "using $deb"
else
  command -v apt-get > /dev/null || die "'apt-get' not found: this script needs a Debian-based system \
(or set DTSL_CGAL_DEMO_DEB to a downloaded libcgal-demo .deb)"
  echo "downloading libcgal-demo with apt-get download (no root needed) ..."
  if ! (cd "$work" && apt-get download libcgal-demo); then
    die "'apt-get download libcgal-demo' failed. Check the network, and that apt knows the package: \
'apt-cache policy libcgal-demo' should show a candidate (if not, an administrator must run \
'apt-get update' once); or set DTSL_CGAL_DEMO_DEB to a downloaded .deb"
  fi
  debs=("$work"/libcgal-demo_*.deb)
  [ -f "${debs[0]}" ] || die "apt-get download reported success but left no libcgal-demo_*.deb in $work"
  deb="${debs[0]}"
fi
version="$(dpkg-deb -f "$deb" Version 2> /dev/null)" || die "$deb is not a valid .deb package"

echo "unpacking $(basename "$deb") ..."
dpkg-deb -x "$deb" "$work/deb" || die "dpkg-deb could not unpack $deb"
tarball="$work/deb/usr/share/doc/libcgal-dev/data.tar.gz"
[ -f "$tarball" ] || die "$(basename "$deb") has no usr/share/doc/libcgal-dev/data.tar.gz; the package layout \
changed (version $version)"

mkdir -p "$work/out"
tar -xzf "$tarball" -C "$work/out" data/meshes data/points_3 ||
  die "could not extract data/meshes and data/points_3 from $tarball"
[ -f "$work/out/data/meshes/fandisk.off" ] || die "extracted data has no data/meshes/fandisk.off"
echo "libcgal-demo $version" > "$work/out/.complete"

# Replace any previous copy (interrupted, or complete with --force): moved aside into $work, which the
# trap removes, so no reader ever sees a half-deleted folder under the cache's name.
if [ -e "$dest" ]; then
  mv "$dest" "$work/old"
fi
mv "$work/out" "$dest"

echo "libcgal-demo $version data in $dest: $(find "$dest/data/meshes" -name '*.off' | wc -l) meshes" \
  "in data/meshes, $(find "$dest/data/points_3" -type f | wc -l) files in data/points_3"
