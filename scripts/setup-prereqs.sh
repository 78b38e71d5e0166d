#!/bin/sh
# The Debian packages `make setup` needs beyond make itself: python3 with venv (Debian's python3
# has no ensurepip without python3-venv) and SWI-Prolog. Installs the missing ones as root, with
# sudo when it is there, or says exactly what to run.
missing=""
command -v python3 >/dev/null 2>&1 || missing="$missing python3"
python3 -c "import ensurepip, venv" >/dev/null 2>&1 || missing="$missing python3-venv"
command -v swipl >/dev/null 2>&1 || missing="$missing swi-prolog-nox"
[ -z "$missing" ] && exit 0

install="apt-get install -y --no-install-recommends$missing"
if ! command -v apt-get >/dev/null 2>&1; then
  echo "make setup: missing:$missing; this is not a Debian system (no apt-get): install Python 3.11+ with venv and SWI-Prolog 9 yourself" >&2
  exit 1
fi
if [ "$(id -u)" = 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1; then
  SUDO="sudo"
else
  echo "make setup: missing Debian packages:$missing; as root run: apt-get update && $install" >&2
  exit 1
fi
echo "make setup: installing$missing from Debian"
$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO $install -qq && exit 0
echo "make setup: the install failed; run: ${SUDO:+sudo }apt-get update && ${SUDO:+sudo }$install" >&2
exit 1
