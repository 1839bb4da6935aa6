"""`python -m helical_sil ...`"""

from helical_sil.cli import main

raise SystemExit(main())
