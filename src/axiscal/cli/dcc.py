"""``axiscal dcc``: sign a Digital Calibration Certificate, check its signature, print its figures."""

from __future__ import annotations

import click


__all__ = ["dcc_group"]


@click.group("dcc")
def dcc_group() -> None:
    """Digital Calibration Certificates: sign, verify, show.

    A DCC (dcc.xml) is written by `axiscal report --certificate` or `--dcc`.
    """


@dcc_group.command("sign")
@click.argument("dcc", type=click.Path(dir_okay=False))
@click.option("--key", required=True, type=click.Path(dir_okay=False), help="The signer's private key (PEM, EC or RSA).")
@click.option("--cert", "cert", required=True, type=click.Path(dir_okay=False), help="The signer's X.509 certificate (PEM).")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The signed DCC to write.")
def sign_command(dcc: str, key: str, cert: str, output: str) -> None:
    """Add an enveloped XML signature to DCC and write it to OUTPUT."""
    from axiscal.report.dcc_sign import sign_dcc

    click.echo(f"signed {sign_dcc(dcc, key, cert, output)}")


@dcc_group.command("verify")
@click.argument("dcc", type=click.Path(dir_okay=False))
@click.option("--cert", "cert", type=click.Path(dir_okay=False),
              help="The signer's certificate (PEM) to hold the signature against [the one the DCC carries].")
def verify_command(dcc: str, cert: str | None) -> None:
    """Check the signature of DCC: exit 0 when valid, 1 (saying what was changed) when not."""
    from axiscal.report.dcc_sign import verify_dcc

    found = verify_dcc(dcc, cert)
    if not found.valid:
        click.echo(f"{dcc}: INVALID: {found.message}", err=True)
        click.get_current_context().exit(1)
    click.echo(f"{dcc}: {found.message}")


@dcc_group.command("show")
@click.argument("dcc", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print the figures as results.json does.")
def show_command(dcc: str, as_json: bool) -> None:
    """Print the figures of DCC, test by test, with their expanded uncertainty."""
    from axiscal.report.dcc import dcc_summary, read_dcc

    read = read_dcc(dcc)
    if as_json:
        from axiscal.io.jsonio import dumps

        click.echo(dumps(read).rstrip())
        return
    click.echo(dcc_summary(read))
