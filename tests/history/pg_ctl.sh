#!/bin/bash
# pg_ctl for the test suite's PostgreSQL server (pytest-postgresql runs this in place of pg_ctl).
# PostgreSQL refuses to run as root. When the tests run as root (CI, containers) the server runs as
# the system's postgres user, with its data folder and log moved out of pytest's private temporary
# folder (which only root may enter) to a folder of that user's, named after the path asked for, so
# that every call for the same data folder finds it; `stop` removes it. The folder asked for is
# made, empty, since pytest-postgresql checks it is there. Debian keeps pg_ctl out of
# PATH, in /usr/lib/postgresql/VERSION/bin.
PG_CTL=$(command -v pg_ctl || ls -d /usr/lib/postgresql/*/bin/pg_ctl 2>/dev/null | sort -V | tail -n 1)
if [ -z "$PG_CTL" ]; then
  echo "pg_ctl not found: install Debian's postgresql (make test does so as root)" >&2
  exit 127
fi
if [ "$(id -u)" != 0 ]; then
  exec "$PG_CTL" "$@"
fi
args=()
home=""
asked=""
prev=""
for arg in "$@"; do
  case "$prev" in
    -D|--pgdata)
      asked="$arg"
      home="${TMPDIR:-/tmp}/axiscal-pg-$(printf %s "$arg" | md5sum | cut -c1-16)"
      arg="$home/data" ;;
    -l|--log)
      arg="${home:-${TMPDIR:-/tmp}/axiscal-pg-log}/server.log" ;;
  esac
  args+=("$arg")
  prev="$arg"
done
if [ -n "$home" ] && [ "$1" = initdb ]; then
  rm -rf "$home"
  install -d -o postgres -m 700 "$home"
  mkdir -p "$asked"  # pytest-postgresql looks for the folder it asked for before asking pg_ctl
fi
runuser -u postgres -- "$PG_CTL" "${args[@]}"
status=$?
if [ -n "$home" ] && [ "$1" = stop ] && [ "$status" = 0 ]; then
  rm -rf "$home"
fi
exit "$status"
