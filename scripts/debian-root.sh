#!/usr/bin/env bash
# A Debian root of a newer release (trixie = Debian 13, forky = Debian testing) on a Debian 12 machine,
# for building and testing the project against that release's ParaView and VTK. Run as root.
#
#   scripts/debian-root.sh SUITE ensure        # create the root (debootstrap) or reuse it, then run
#                                              # scripts/install-deps.sh inside it (idempotent)
#   scripts/debian-root.sh SUITE run CMD ...   # run CMD inside the root, in the repository
#   scripts/debian-root.sh SUITE path          # print the root's folder
#   scripts/debian-root.sh SUITE clean-ensure  # a *clean* root: debootstrap minbase and the package
#                                              # lists, nothing else (scripts/test-package.sh copies it)
#
# SUITE: trixie or forky (bookworm too for clean-ensure). The root lives in $AMRSP_ROOTS_DIR/SUITE
# (default /var/cache/amrsp/roots), the clean one in $AMRSP_ROOTS_DIR/clean-SUITE, both copies of the
# one debootstrap in $AMRSP_ROOTS_DIR/minbase-SUITE (bookworm's clean root is its own); delete a
# folder to start over. AMRSP_ROOT_DIR=DIR makes `run` use the root in DIR (a copy of a clean root),
# and AMRSP_ROOT_APT_ARCHIVES=DIR mounts DIR as its /var/cache/apt/archives (packages downloaded
# once).
# Inside a root the repository is mounted at /amrsp/src and ../shared at /amrsp/shared (so the repository's ../shared is the same data), /tmp/.X11-unix is the
# host's (the X server of scripts/start-xvfb.sh serves GLX-only ParaView builds), and /proc, /sys, /dev
# are the host's. The mounts live in a private mount namespace (unshare): they disappear when the
# command ends, whatever way it ends; nothing is left mounted on the host.
# The mirror is the one apt already uses on this machine (its sources), so no other host is contacted.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
suite=${1:?usage: scripts/debian-root.sh trixie|forky ensure|run CMD...|path}
action=${2:?usage: scripts/debian-root.sh SUITE ensure|run CMD...|path}
shift 2
case "$suite" in
  trixie|forky) ;;
  bookworm) [ "$action" = clean-ensure ] || [ -n "${AMRSP_ROOT_DIR:-}" ] \
    || { echo "debian-root: bookworm is this host's release: only clean-ensure, or run with AMRSP_ROOT_DIR" >&2; exit 2; } ;;
  *) echo "debian-root: unknown suite '$suite' (trixie or forky; bookworm for clean-ensure)" >&2; exit 2 ;;
esac
roots=${AMRSP_ROOTS_DIR:-/var/cache/amrsp/roots}
root=${AMRSP_ROOT_DIR:-$roots/$suite}
log() { printf '[root %s] %s\n' "$suite" "$*"; }
die() { printf '[root %s] ERROR: %s\n' "$suite" "$*" >&2; exit 1; }

# The Debian mirror apt uses here: the first "debian" URI of the deb822 or one-line sources.
host_mirror() {
  local uri
  uri=$(cat /etc/apt/sources.list.d/*.sources 2>/dev/null \
        | awk '/^URIs:/{u=$2} /^Suites:/{ if ($0 ~ /bookworm( |$)/ && u != "") {print u; exit} }')
  if [ -z "$uri" ]; then
    uri=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null \
          | awk '$1 == "deb" && $3 ~ /^bookworm$/ {print $2; exit}')
  fi
  [ -n "$uri" ] || die "no Debian mirror for bookworm found in /etc/apt/sources.list{,.d}"
  printf '%s\n' "${uri%/}"
}

# run_in_root CMD...: CMD inside the root, with the mounts described above, in a clean environment
# that keeps only the variables the project's scripts read.
run_in_root() {
  [ -x "$root/bin/bash" ] || die "no root at $root (run: scripts/debian-root.sh $suite ensure)"
  local keep=() v
  for v in $(compgen -e); do
    case "$v" in
      AMRSP_*|CI|TERM|DEBIAN_FRONTEND) keep+=("$v=${!v}") ;;
    esac
  done
  local shared
  shared=$(cd "$repo/.." && pwd)/shared
  # shellcheck disable=SC2016  # expanded by the inner shell
  unshare --mount --propagation private -- /bin/bash -c '
    set -e
    root=$1 repo=$2 shared=$3 archives=$4; shift 4
    mkdir -p "$root/amrsp/src" "$root/amrsp/shared" "$root/tmp/.X11-unix"
    mount -t proc proc "$root/proc"
    mount --rbind /sys "$root/sys"
    mount --rbind /dev "$root/dev"
    mount --bind "$repo" "$root/amrsp/src"
    if [ -d "$shared" ]; then mount --bind "$shared" "$root/amrsp/shared"; fi
    if [ -d /tmp/.X11-unix ]; then mount --bind /tmp/.X11-unix "$root/tmp/.X11-unix"; fi
    if [ -n "$archives" ]; then mount --bind "$archives" "$root/var/cache/apt/archives"; fi
    cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
    exec chroot "$root" "$@"
  ' amrsp-root "$root" "$repo" "$shared" "${AMRSP_ROOT_APT_ARCHIVES:-}" \
    /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      LANG=C.UTF-8 "${keep[@]}" /bin/bash -c 'cd /amrsp/src && exec "$@"' amrsp-cmd "$@"
}

# bootstrap DIR: a minbase root of $suite from the host's mirror in DIR (made in DIR.tmp, then moved)
bootstrap() {
  local dir=$1 mirror
  mirror=$(host_mirror)
  command -v debootstrap >/dev/null || die "debootstrap is missing (scripts/install-deps.sh installs it)"
  # bookworm's debootstrap has no script named forky; the sid script bootstraps any recent suite
  local script=/usr/share/debootstrap/scripts/sid
  rm -rf "$dir.tmp"
  mkdir -p "$roots"
  log "debootstrap $suite from $mirror into $dir (about 1 min)"
  if ! debootstrap --variant=minbase "$suite" "$dir.tmp" "$mirror" "$script" \
      >"$dir-debootstrap.log" 2>&1; then
    tail -n 20 "$dir-debootstrap.log" >&2
    die "debootstrap failed (log: $dir-debootstrap.log)"
  fi
  printf 'deb %s %s main\n' "$mirror" "$suite" >"$dir.tmp/etc/apt/sources.list"
  # The mirror may serve a frozen snapshot whose Release files are past their Valid-Until date.
  echo 'Acquire::Check-Valid-Until "false";' >"$dir.tmp/etc/apt/apt.conf.d/99amrsp-mirror"
  # A root is a cache that can be made again: dpkg need not sync every file (much faster unpacking).
  echo force-unsafe-io >"$dir.tmp/etc/dpkg/dpkg.cfg.d/amrsp-unsafe-io"
  printf 'suite=%s\nmirror=%s\n' "$suite" "$mirror" >"$dir.tmp/.amrsp-root"
  rm -rf "$dir"
  mv "$dir.tmp" "$dir"
}

# made_this_week FILE: FILE exists and is less than 7 days old (a root made from older package lists
# is made again)
made_this_week() {
  [ -f "$1" ] && [ -n "$(find "$1" -mtime -7 2>/dev/null)" ]
}

# minbase DIR: DIR becomes a minbase root of $suite. A newer release's build root and its clean root
# both start as minbase: one debootstrap serves both, kept in $roots/minbase-$suite (made again after
# a week, like the clean root) and copied; flock lets the second caller wait for the first.
minbase() {
  local dir=$1 base=$roots/minbase-$suite
  if [ "$suite" = bookworm ]; then bootstrap "$dir"; return; fi  # only the clean root starts from it
  mkdir -p "$roots"
  (
    flock 7
    if made_this_week "$base/.amrsp-root"; then
      log "copying the minbase root $base into $dir"
    else
      bootstrap "$base"
    fi
    rm -rf "$dir.tmp"
    cp -a "$base" "$dir.tmp"
    rm -rf "$dir"
    mv "$dir.tmp" "$dir"
  ) 7>"$roots/minbase-$suite.lock"
}

# The two phases print their wall seconds on lines of their own, which scripts/test.sh reads for
# its phase timings: "[root SUITE] phase root: N s" (debootstrap; 0 when reused) and
# "[root SUITE] phase install: N s" (the packages inside the root).
ensure_root() {
  local t0=$SECONDS
  if [ ! -f "$root/.amrsp-root" ]; then
    minbase "$root"
  else
    log "reusing $root"
  fi
  log "phase root: $((SECONDS - t0)) s"
  local t1=$SECONDS
  log "installing $suite's packages inside the root (log: $root/tmp/amrsp-install-deps.log)"
  if ! run_in_root scripts/install-deps.sh >"$root/tmp/amrsp-install-deps.log" 2>&1; then
    tail -n 40 "$root/tmp/amrsp-install-deps.log" >&2
    die "installing the packages inside the root failed"
  fi
  grep -E '^\[install-deps\] (all done|ParaView|VTK)' "$root/tmp/amrsp-install-deps.log" | sed "s/^/[root $suite] /" || true
  log "phase install: $((SECONDS - t1)) s"
  log "ready in $((SECONDS - t0)) s ($(du -sh "$root" 2>/dev/null | cut -f1))"
}

# The clean root: minbase and fresh package lists, never changed afterwards (its users copy it).
# Remade when older than a week, so that its lists follow the mirror.
clean_ensure() {
  local t0=$SECONDS clean=$roots/clean-$suite
  mkdir -p "$roots"
  exec 8>"$roots/clean-$suite.lock"
  flock 8  # one maker at a time; a second caller finds the root made
  if made_this_week "$clean/.amrsp-clean"; then
    log "reusing the clean root $clean"
    return 0
  fi
  minbase "$clean.new"
  root=$clean.new  # the root run_in_root enters
  run_in_root apt-get -q -o Acquire::Check-Valid-Until=false update >"$root/tmp/apt-update.log" 2>&1 \
    || { tail -n 20 "$root/tmp/apt-update.log" >&2; die "apt-get update in the clean root failed"; }
  touch "$clean.new/.amrsp-clean"
  rm -rf "$clean"
  mv "$clean.new" "$clean"
  log "clean root ready in $((SECONDS - t0)) s ($(du -sh "$clean" 2>/dev/null | cut -f1))"
}

case "$action" in
  ensure) ensure_root ;;
  clean-ensure) clean_ensure ;;
  run) [ "$#" -gt 0 ] || die "run needs a command"; run_in_root "$@" ;;
  path) printf '%s\n' "$root" ;;
  *) die "unknown action '$action' (ensure, clean-ensure, run or path)" ;;
esac
