"""Where the programs and logs are in the smstestbed repository, and the thresholds used to
judge runs and lines."""

import re


# The programs whose runs may be used to choose settings, and the ones kept for an
# independent check only (never used to fit anything; printed in their own table).
NC_DIR = 'tdp/mtc/NC-Code'
MAIN_PROGRAMS = {
    'OP1': 'NIST_MTC_CRADA_BOX_REV-A OP1 (Bottom).NC',
    'OP2': 'NIST_MTC_CRADA_BOX_REV-A OP2 (Front).NC',
    'OP3': 'NIST_MTC_CRADA_BOX_REV-A OP3 (Back).NC',
}
CHECK_PATTERN = re.compile(r'NIST_MTC_CRADA_(BOX_REV-A (OP4|OP5)|COVER_REV-A|PLATE-\d+)\b.*\.NC$')

# Where the logs are. tdp/mtc/PartData is left out: its files are the Split files joined per
# part (the same samples again). tdp/mtc/Raw is left out: Clean holds the same days cleaned.
LOG_DIRS = ('tdp/mtc/Clean', 'tdp/mtc/Split', 'raw')
LOG_FILE = re.compile(r'(^tdp/mtc/(Clean|Split)/[^/]+\.txt$)|(^raw/Hurco\d\d/[^/]+\.txt$)')

MIN_BLOCK_S = 0.5        # blocks shorter than this are below the log's time resolution
FEED_RATIO_TOL = 0.02    # measured path speed / programmed F must be within this of 1.00
LONG_STALL_S = 60.0      # one line taking longer than this means the run was held
CHECK_RATIO_TOL = 0.10   # the check programs' short moves keep their speed below F: looser
IN_MM = 25.4
