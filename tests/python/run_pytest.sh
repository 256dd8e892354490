#!/bin/sh
# run_pytest.sh PYTHON DIR: the package's tests under PYTHON, skipped (77)
# with the reason where PYTHON lacks numpy (the package needs it) or pytest,
# as on a bare GPU machine a build was carried to.
python=$1 dir=$2
"$python" -c 'import numpy' 2>/dev/null || { echo "SKIP: $python has no numpy"; exit 77; }
"$python" -c 'import pytest' 2>/dev/null || { echo "SKIP: $python has no pytest"; exit 77; }
exec "$python" -m pytest -q -p no:cacheprovider "$dir"
