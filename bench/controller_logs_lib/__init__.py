"""ncjoule's predicted times against the NIST smstestbed controller logs, for
bench/controller_logs.py: reading the repository, its programs and logs, cutting the logs
into runs, choosing the runs to compare, running ncjoule, and printing the report."""
