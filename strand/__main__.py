from strand.cli import main

raise SystemExit(main())
