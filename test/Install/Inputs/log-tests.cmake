
# Appended by test/Install/log-tests.test: the striker's recordings
# replayed in CTest, a corpus that passes and one that fails.
enable_testing()
bscript_add_log_tests(NAME striker_logs_pass
  BEHAVIOR_TARGET striker
  LOGS ${LOGS}/pass
  JOBS 2
  JUNIT striker-pass.xml)
bscript_add_log_tests(NAME striker_logs_fail
  BEHAVIOR_TARGET striker
  LOGS ${LOGS}/fail)
