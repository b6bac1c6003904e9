#!/bin/bash
# One campaign for issue 14's targets: one binary, one bench invocation, every row.
set -u
cd /work/main
BIN=/tmp/fcsolve-one; OUT=/tmp/campaign-one
export OPENBLAS_NUM_THREADS=1
S=auto,nsgs,nsgs-ac,vi-fp,nsn-ac,nsn-ac-hybrid,nsn-jm,nipm,aclm-newton,ppa,ppa-nsgs,nsn-ac-global,nsn-jm-global,nsn-nm-global,nsn-fb-global
FILES=$(/usr/bin/python3 -c "import csv; print(' '.join('/tmp/fcsolve-corpus/'+r['file'] for r in csv.DictReader(open('/tmp/fcsolve-corpus/MANIFEST.csv')) if (r['kind'] == 'global') == r['scene'].startswith('fem')))")
echo "files: $(echo $FILES | wc -w) corpus + shared; start $(date)"
$BIN bench /work/shared/data/fclib/local /work/shared/data/fclib/global $FILES --solvers $S --tol 1e-8,1e-4 --timeout 60 --jobs 2 --out $OUT
echo "done $(date)"
/usr/bin/python3 bench/auto_targets.py $OUT --manifest /tmp/fcsolve-corpus/MANIFEST.csv --details --fcsolve-only > $OUT/targets.txt
echo CAMPAIGN-DONE
