"""alembic's environment for the calibration history: migrations run on the connection axiscal gives.

axiscal opens the connection, takes the lock that serialises writers (``BEGIN IMMEDIATE`` on
SQLite, an advisory lock on PostgreSQL) and passes the connection in ``config.attributes``; the
migrations run inside that transaction, so two processes opening a new database at once make its
tables once.
"""

from alembic import context

connection = context.config.attributes["connection"]
context.configure(connection=connection, render_as_batch=connection.dialect.name == "sqlite")
with context.begin_transaction():
    context.run_migrations()
