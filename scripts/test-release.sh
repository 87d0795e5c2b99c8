#!/usr/bin/env bash
# Run the README's commands on another Debian release, on this machine: make a
# root for RELEASE with debootstrap under build/releases/RELEASE, copy the tree
# into it, and run scripts/test.sh there through chroot. test.sh installs the
# release's own packages (scripts/install-deps.sh knows each release's names).
#
# Usage: scripts/test-release.sh RELEASE [test.sh arguments]
#        scripts/test-release.sh RELEASE --shell [command...]
#   RELEASE: bookworm (Debian 12: VTK 9.1, ParaView 5.11), trixie (Debian 13:
#            VTK 9.3, ParaView 5.13) or forky (testing: VTK 9.6, ParaView 6.1)
#   --shell  run a command (default: an interactive bash) in the root's copy
#            of the tree instead of test.sh
#   Examples: scripts/test-release.sh forky
#             scripts/test-release.sh forky paraview
#             scripts/test-release.sh trixie vtk -- -L 'unit|egl'
#
# The root is reused while it is complete and was made by this same script
# with the same base packages; a root whose making stopped halfway is deleted
# and made again, never reused. Nothing outside build/releases/RELEASE is
# written; /proc, /sys and /dev are bind-mounted into the root only while it
# runs. Needs root (or sudo), debootstrap and the network to Debian's mirror.
# POINTSURFACES_DEBIAN_MIRROR overrides the mirror (default: this machine's).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
die() { echo "test-release.sh: $*" >&2; exit 1; }

[ $# -ge 1 ] || { sed -n '7,16p' "$0" >&2; exit 2; }
release=$1
shift
case "$release" in
  bookworm|trixie|forky) ;;
  -h|--help) sed -n '2,23p' "$0"; exit 0 ;;
  *) die "unknown release '$release' (bookworm, trixie or forky)" ;;
esac

SUDO=""
if [ "$(id -u)" != 0 ]; then
  command -v sudo >/dev/null && sudo -n true 2>/dev/null \
    || die "$release: needs root (or password-less sudo) for debootstrap and chroot"
  SUDO="sudo -n"
fi
for tool in debootstrap chroot mount git; do
  command -v "$tool" >/dev/null 2>&1 || [ -x "/usr/sbin/$tool" ] \
    || die "$release: '$tool' is missing (scripts/install-deps.sh installs it)"
done
export PATH="$PATH:/usr/sbin:/sbin"

dir="$here/build/releases/$release"
root="$dir/root"
# What the base root holds; a change here makes the root again.
base="ca-certificates,git,sudo,locales-all"
mirror=${POINTSURFACES_DEBIAN_MIRROR:-}
if [ -z "$mirror" ]; then
  mirror=$(grep -hoE '^(URIs:|deb) +https?://[^ ]+/debian/?( |$)' \
    /etc/apt/sources.list /etc/apt/sources.list.d/* 2>/dev/null \
    | head -n1 | awk '{print $2}' || true)
  mirror=${mirror:-http://deb.debian.org/debian}
fi
stamp="release=$release base=$base mirror=$mirror script=3"

mounted=()
cleanup() {
  local m
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    m=${mounted[$i]}
    $SUDO umount -l "$m" 2>/dev/null || true
  done
}
trap cleanup EXIT

if [ -d "$root" ] && [ "$(cat "$dir/complete" 2>/dev/null)" != "$stamp" ]; then
  echo "test-release.sh: $release: removing an incomplete or outdated root" >&2
  # A root left mounted by a killed run: unmount before deleting.
  for m in dev/pts dev/shm dev proc sys ""; do
    if mountpoint -q "$root/$m" 2>/dev/null; then $SUDO umount -l "$root/$m"; fi
  done
  $SUDO rm -rf --one-file-system "$root" "$dir/complete"
fi

if [ ! -d "$root" ]; then
  mkdir -p "$dir"
  script=$release
  [ -e "/usr/share/debootstrap/scripts/$release" ] || script=sid
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  # forky's archive is signed with keys newer than an old host's keyring:
  # take the keyring of a trixie root when there is one.
  if [ "$release" = forky ] && [ -f "$here/build/releases/trixie/root$keyring" ]; then
    keyring="$here/build/releases/trixie/root$keyring"
  fi
  echo "test-release.sh: $release: debootstrap from $mirror (a few minutes)" >&2
  if ! $SUDO debootstrap --variant=minbase --include="$base" \
      --keyring="$keyring" "$release" "$root" "$mirror" \
      "/usr/share/debootstrap/scripts/$script" >"$dir/debootstrap.log" 2>&1; then
    die "$release: step 'debootstrap' failed (log: $dir/debootstrap.log)"
  fi
  echo "deb $mirror $release main" | $SUDO tee "$root/etc/apt/sources.list" >/dev/null
  # A mirror that is a dated snapshot serves Release files past their
  # Valid-Until: accept them inside the root only.
  echo 'Acquire::Check-Valid-Until "false";' \
    | $SUDO tee "$root/etc/apt/apt.conf.d/99pointsurfaces-snapshot" >/dev/null
  echo "$stamp" >"$dir/complete"
fi

# The tree: tracked and untracked-but-not-ignored files, as a fresh clone plus
# the working changes; build/ inside the root is kept between runs. What an
# earlier copy left (a file since moved or deleted) goes first, or it would
# shadow the moved file on an include path.
src="$root/work/pointsurfaces"
$SUDO mkdir -p "$src"
$SUDO find "$src" -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
(cd "$here" && git ls-files -z -co --exclude-standard) \
  | (cd "$here" && $SUDO tar --null -T - -cf - 2>/dev/null) \
  | (cd "$src" && $SUDO tar -xf -)
$SUDO cp /etc/resolv.conf "$root/etc/resolv.conf"

# The root is made a mount point of its own, so that unshare --mount inside
# it (the GPU bundle's test) can change its propagation.
$SUDO mount --bind "$root" "$root"
mounted+=("$root")
for m in proc sys dev dev/pts dev/shm; do
  $SUDO mkdir -p "$root/$m"
  case "$m" in
    proc) $SUDO mount -t proc proc "$root/proc" ;;
    sys) $SUDO mount -t sysfs sys "$root/sys" ;;
    dev/shm) $SUDO mount -t tmpfs shm "$root/dev/shm" ;;
    *) $SUDO mount --bind "/$m" "$root/$m" ;;
  esac
  mounted+=("$root/$m")
done

env_args=(HOME=/root LANG=C.UTF-8 PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
  DEBIAN_FRONTEND=noninteractive CI="${CI:-}" CTEST_OUTPUT_ON_FAILURE=1 TERM="${TERM:-dumb}")
if [ "${1:-}" = --shell ]; then
  shift
  [ $# -gt 0 ] || set -- bash
  $SUDO chroot "$root" /usr/bin/env -i "${env_args[@]}" bash -c 'cd /work/pointsurfaces && exec "$@"' bash "$@"
else
  echo "test-release.sh: $release: scripts/test.sh $*" >&2
  $SUDO chroot "$root" /usr/bin/env -i "${env_args[@]}" \
    /work/pointsurfaces/scripts/test.sh "$@"
fi
