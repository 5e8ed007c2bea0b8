# SPDX-License-Identifier: Apache-2.0
"""Every source file of the repository carries the SPDX licence line (scripts/flow/spdx.py)."""
from __future__ import annotations

from scripts.flow import spdx


def test_every_source_file_has_the_spdx_line(capsys):
    assert spdx.main([]) == 0, capsys.readouterr().out


def test_add_tag_keeps_shebang_and_capi_first():
    assert spdx.add_tag("#!/bin/sh\necho\n", "#").splitlines()[:2] == [
        "#!/bin/sh", "# SPDX-License-Identifier: Apache-2.0"]
    assert spdx.add_tag("CAPI=2:\nname: x\n", "#").splitlines()[1].endswith("Apache-2.0")
    assert spdx.add_tag("module m; endmodule\n", "//").startswith("// SPDX-License-Identifier:")


def test_a_file_without_the_line_is_found(tmp_path, monkeypatch):
    (tmp_path / "a.sv").write_text("module a; endmodule\n")
    (tmp_path / "b.py").write_text("# SPDX-License-Identifier: Apache-2.0\n")
    (tmp_path / "c.json").write_text("{}\n")
    monkeypatch.setattr(spdx, "ROOT", tmp_path)
    monkeypatch.setattr(spdx, "tracked_files", lambda: sorted(tmp_path.iterdir()))
    assert spdx.main([]) == 1
