#!/bin/sh
# Runs tests/cli/run_outputs.py with a Python that has VTK's bindings
# (python3-vtk9: Debian's /usr/bin/python3 when another python3 comes first
# on the PATH).
# usage: run_outputs.sh DEMVV CASES_DIR WORK_DIR
for python in python3 /usr/bin/python3; do
  if "$python" -c "import vtkmodules.vtkIOXML" 2>/dev/null; then
    exec "$python" "$(dirname "$0")/run_outputs.py" "$@"
  fi
done
echo "FAIL: no python3 with VTK's bindings (install python3-vtk9)"
exit 1
