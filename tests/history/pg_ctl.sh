#!/bin/sh
# pg_ctl for the test suite's PostgreSQL server (pytest-postgresql runs this in place of pg_ctl).
# PostgreSQL refuses to run as root; when the tests run as root (CI, containers) the server runs as
# the system's postgres user, in a data folder handed to that user. Debian keeps pg_ctl out of PATH,
# in /usr/lib/postgresql/VERSION/bin.
PG_CTL=$(command -v pg_ctl || ls -d /usr/lib/postgresql/*/bin/pg_ctl 2>/dev/null | sort -V | tail -n 1)
if [ -z "$PG_CTL" ]; then
  echo "pg_ctl not found: install Debian's postgresql (make test does so as root)" >&2
  exit 127
fi
if [ "$(id -u)" != 0 ]; then
  exec "$PG_CTL" "$@"
fi
data=""
prev=""
for arg in "$@"; do
  case "$prev" in -D|--pgdata) data="$arg" ;; esac
  prev="$arg"
done
case "$1" in
  initdb|start)
    if [ -n "$data" ]; then
      folder=$(dirname "$data")
      chown -R postgres "$folder"
      up="$folder"
      while [ "$up" != / ]; do chmod o+x "$up"; up=$(dirname "$up"); done
    fi ;;
esac
exec runuser -u postgres -- "$PG_CTL" "$@"
