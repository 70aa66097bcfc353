#!/bin/sh
# The file-based route: one program writes samples, another answers pdf queries (any language).
set -e
here=$(dirname "$0")
python=${PYTHON:-/usr/bin/python3}
"$python" "$here/power_cosine_samples.py"  # writes samples.csv: "x,y,z" per line
${CHI2:-build/bin/chi2} check --domain hemisphere --samples samples.csv \
  --pdf-cmd "$python $here/power_cosine_pdf.py" --images chi2_images --json
