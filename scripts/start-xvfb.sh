# shellcheck shell=sh
# Make sure an X server is available for GLX rendering (VTK/ParaView on Debian render through GLX only).
#
#   . scripts/start-xvfb.sh      # source it: DISPLAY is exported in the calling shell
#   bash scripts/start-xvfb.sh   # or run it: it prints the `export DISPLAY=...` line to use
#
# If $DISPLAY already answers, nothing is done. Otherwise `Xvfb :99 -screen 0 1280x1024x24 -noreset` is started
# in the background (unless an X server on :99 is already running), and the script waits until it answers.
# -noreset: an X server resets when its last client disconnects, and closes the connections that arrive
# meanwhile without a reply (strace: the setup request written, then POLLHUP); VTK then aborts with "bad X server
# connection". Tests that open and close windows one after another hit that window all the time (5 of 8 runs of
# one test under load); without the reset they never do.
# AMRSP_XVFB_DISPLAY overrides the display number (default :99). Xvfb's log goes to /tmp/amrsp-xvfb-<n>.log.
# The caller's shell options are not touched (no `set`); the helper names are unset before returning.

_amrsp_xvfb_probe() {
  # Does the X display "$1" answer, with the GLX extension VTK's windows need? Plain GL env so a zink
  # setting in the caller cannot make the probe fail.
  if command -v xdpyinfo >/dev/null 2>&1; then
    DISPLAY="$1" xdpyinfo 2>/dev/null | grep -qE '^[[:space:]]+GLX$' && return 0
  fi
  if command -v glxinfo >/dev/null 2>&1; then
    DISPLAY="$1" env -u MESA_LOADER_DRIVER_OVERRIDE -u LIBGL_ALWAYS_SOFTWARE glxinfo -B >/dev/null 2>&1 && return 0
  fi
  return 1
}

_amrsp_xvfb_main() {
  _amrsp_d="${AMRSP_XVFB_DISPLAY:-:99}"
  _amrsp_n="${_amrsp_d#:}"
  _amrsp_n="${_amrsp_n%%.*}"

  if [ -n "${DISPLAY:-}" ] && _amrsp_xvfb_probe "$DISPLAY"; then
    echo "start-xvfb: DISPLAY=$DISPLAY already works, nothing to do"
    return 0
  fi

  # an Xvfb of ours (its log is there) started without -noreset: replace it (see above)
  if [ -f "/tmp/amrsp-xvfb-$_amrsp_n.log" ]; then
    for _amrsp_p in /proc/[0-9]*; do
      _amrsp_cmd=$(tr '\0' ' ' <"$_amrsp_p/cmdline" 2>/dev/null || true)
      case "$_amrsp_cmd" in
        "Xvfb :$_amrsp_n "*-noreset*) ;;
        "Xvfb :$_amrsp_n "*)
          _amrsp_pid=${_amrsp_p#/proc/}
          echo "start-xvfb: restarting our Xvfb :$_amrsp_n (pid $_amrsp_pid) with -noreset"
          kill "$_amrsp_pid" 2>/dev/null || true
          _amrsp_i=0
          while kill -0 "$_amrsp_pid" 2>/dev/null && [ "$_amrsp_i" -lt 50 ]; do
            _amrsp_i=$((_amrsp_i + 1))
            sleep 0.1
          done
          rm -f "/tmp/.X$_amrsp_n-lock" "/tmp/.X11-unix/X$_amrsp_n" ;;
      esac
    done
  fi

  if ! _amrsp_xvfb_probe ":$_amrsp_n"; then
    if ! command -v Xvfb >/dev/null 2>&1; then
      echo "start-xvfb: ERROR: Xvfb not installed (apt-get install xvfb xauth), and no working DISPLAY" >&2
      return 1
    fi
    # A lock without a live server is stale (a crashed Xvfb): remove it, otherwise Xvfb refuses to start.
    if [ -f "/tmp/.X$_amrsp_n-lock" ]; then
      _amrsp_pid=$(tr -d ' ' <"/tmp/.X$_amrsp_n-lock" 2>/dev/null || true)
      if [ -z "$_amrsp_pid" ] || ! kill -0 "$_amrsp_pid" 2>/dev/null; then
        rm -f "/tmp/.X$_amrsp_n-lock" "/tmp/.X11-unix/X$_amrsp_n"
      fi
    fi
    if [ ! -f "/tmp/.X$_amrsp_n-lock" ]; then
      echo "start-xvfb: starting Xvfb :$_amrsp_n -screen 0 1280x1024x24 -noreset (log /tmp/amrsp-xvfb-$_amrsp_n.log)"
      # Detached, with no inherited stdio, so that a CI step that sourced this script does not wait on it.
      if command -v setsid >/dev/null 2>&1; then
        setsid -f Xvfb ":$_amrsp_n" -screen 0 1280x1024x24 -nolisten tcp -noreset \
          </dev/null >"/tmp/amrsp-xvfb-$_amrsp_n.log" 2>&1
      else
        nohup Xvfb ":$_amrsp_n" -screen 0 1280x1024x24 -nolisten tcp -noreset \
          </dev/null >"/tmp/amrsp-xvfb-$_amrsp_n.log" 2>&1 &
      fi
    else
      echo "start-xvfb: an X server for :$_amrsp_n is already running (pid $(tr -d ' ' <"/tmp/.X$_amrsp_n-lock" 2>/dev/null || true)), waiting for it"
    fi
    _amrsp_i=0
    until _amrsp_xvfb_probe ":$_amrsp_n"; do
      _amrsp_i=$((_amrsp_i + 1))
      if [ "$_amrsp_i" -ge 100 ]; then
        echo "start-xvfb: ERROR: X server :$_amrsp_n did not answer within 20 s; see /tmp/amrsp-xvfb-$_amrsp_n.log" >&2
        return 1
      fi
      sleep 0.2
    done
  fi
  DISPLAY=":$_amrsp_n"
  export DISPLAY
  echo "start-xvfb: X server :$_amrsp_n is up; use:  export DISPLAY=:$_amrsp_n"
  return 0
}

_amrsp_xvfb_main
_amrsp_xvfb_rc=$?
unset -f _amrsp_xvfb_probe _amrsp_xvfb_main
unset _amrsp_d _amrsp_n _amrsp_pid _amrsp_i _amrsp_cmd _amrsp_p
# `return` works only when sourced; when executed, it fails and `exit` runs instead.
eval "unset _amrsp_xvfb_rc; return $_amrsp_xvfb_rc 2>/dev/null || exit $_amrsp_xvfb_rc"
