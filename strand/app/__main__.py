from strand.app.cli import main

raise SystemExit(main())
