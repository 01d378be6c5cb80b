"""Signing a DCC and checking its signature (XML Signature, enveloped, with signxml).

:func:`sign_dcc` adds an enveloped ``ds:Signature`` (ECDSA or RSA with SHA-256, exclusive
canonicalisation, the signer's X.509 certificate in ``ds:KeyInfo``) over the whole certificate.
Before signing it writes, in the DCC's ``dcc:comment`` (which the schema leaves open to any
content), a SHA-256 digest of each part: the administrative data and each measurementResult. The
signature covers those digests too, so when :func:`verify_dcc` finds the signature broken it can
say which part was changed since signing (the test's id, or "the administrative data").
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.report.dcc import DCC_NS

__all__ = ["PARTS_NS", "sign_dcc", "verify_dcc", "Verification"]

#: the namespace of the part digests axiscal keeps in the signed DCC's comment
PARTS_NS = "urn:axiscal:dcc-parts"
_DS = "http://www.w3.org/2000/09/xmldsig#"


@dataclass(frozen=True)
class Verification:
    """What :func:`verify_dcc` found.

    Attributes
    ----------
    valid : bool
    signer : str
        The signing certificate's subject.
    message : str
        One line: what was checked, or what was changed.
    changed : tuple of str
        The parts changed since signing (empty when valid or unknown).
    """

    valid: bool
    signer: str
    message: str
    changed: tuple[str, ...] = ()


def _parse(path: Path):
    from lxml import etree

    try:
        return etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True)).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        raise AxiscalError(f"not a readable XML file: {exc}", path=path) from None


def _parts(root) -> dict[str, str]:
    """SHA-256 of each part's exclusive canonical form: administrativeData and each measurementResult."""
    from lxml import etree

    out = {}
    for element in root:
        name = etree.QName(element).localname if isinstance(element.tag, str) else ""
        if name == "administrativeData":
            out["the administrative data"] = element
        elif name == "measurementResults":
            for index, result in enumerate(element, start=1):
                if isinstance(result.tag, str):
                    ref = result.get("refType", "")
                    label = ref.split(":", 1)[1] if ref.startswith("axiscal_test:") else f"measurementResult {index}"
                    out[f"measurementResult '{label}'"] = result
    return {name: hashlib.sha256(etree.tostring(el, method="c14n", exclusive=True)).hexdigest()
            for name, el in out.items()}


def _read_pem(path: str | Path, what: str) -> bytes:
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise AxiscalError(f"cannot read the {what}: {exc.strerror}", path=path) from None
    if b"-----BEGIN" not in data:
        raise AxiscalError(f"not a PEM file (the {what})", path=path)
    return data


def sign_dcc(dcc: str | Path, key: str | Path, cert: str | Path, output: str | Path,
             *, passphrase: bytes | None = None) -> Path:
    """Sign ``dcc`` with ``key`` and write the signed DCC to ``output`` (atomically).

    Parameters
    ----------
    dcc : str or Path
        A DCC (unsigned).
    key, cert : str or Path
        The signer's private key and X.509 certificate, PEM.
    output : str or Path
    passphrase : bytes, keyword-only
        Of an encrypted key.

    Returns
    -------
    Path
        ``output``.

    Raises
    ------
    AxiscalError
        For a file that is not a DCC, one already signed, a key or certificate that cannot be read
        or that do not belong together.
    """
    from lxml import etree
    from signxml import XMLSigner, methods
    from signxml.exceptions import InvalidInput, SignXMLException

    from axiscal.io.atomic import atomic_write

    from axiscal.io.arguments import check_path

    dcc, output = check_path("dcc", dcc), check_path("output", output)
    key, cert = check_path("key", key), check_path("cert", cert)
    if passphrase is not None and not isinstance(passphrase, bytes):
        raise AxiscalError(f"passphrase must be bytes, not {type(passphrase).__name__}")
    root = _parse(dcc)
    if root.tag != f"{{{DCC_NS}}}digitalCalibrationCertificate":
        raise AxiscalError("not a Digital Calibration Certificate (root dcc:digitalCalibrationCertificate)", path=dcc)
    if root.find(f"{{{_DS}}}Signature") is not None:
        raise AxiscalError("this DCC is signed already", path=dcc)
    key_pem, cert_pem = _read_pem(key, "private key"), _read_pem(cert, "certificate")
    comment = root.find(f"{{{DCC_NS}}}comment")
    if comment is None:
        comment = etree.Element(f"{{{DCC_NS}}}comment")
        results = root.find(f"{{{DCC_NS}}}measurementResults")
        results.addnext(comment)
    for old in comment.findall(f"{{{PARTS_NS}}}parts"):
        comment.remove(old)
    parts = etree.SubElement(comment, f"{{{PARTS_NS}}}parts", nsmap={"parts": PARTS_NS})
    for name, digest in _parts(root).items():
        etree.SubElement(parts, f"{{{PARTS_NS}}}part", name=name, sha256=digest)
    from cryptography.hazmat.primitives.serialization import load_pem_private_key

    try:
        private = load_pem_private_key(key_pem, password=passphrase)
    except (ValueError, TypeError) as exc:
        raise AxiscalError(f"cannot load the private key: {exc}", path=key) from None
    from cryptography.hazmat.primitives.asymmetric import ec, rsa

    if isinstance(private, ec.EllipticCurvePrivateKey):
        algorithm = "ecdsa-sha256"
    elif isinstance(private, rsa.RSAPrivateKey):
        algorithm = "rsa-sha256"
    else:
        raise AxiscalError("the private key must be an EC or RSA key", path=key)
    signer = XMLSigner(method=methods.enveloped, signature_algorithm=algorithm, digest_algorithm="sha256",
                       c14n_algorithm="http://www.w3.org/2001/10/xml-exc-c14n#")
    _check_pair(private, cert_pem, cert)
    try:
        signed = signer.sign(root, key=private, cert=cert_pem.decode("ascii"))
    except (InvalidInput, SignXMLException, ValueError) as exc:
        raise AxiscalError(f"signing failed: {exc}", path=dcc) from None
    data = etree.tostring(signed, xml_declaration=True, encoding="utf-8")
    atomic_write(output, lambda temporary: temporary.write_bytes(data))
    return output


def _check_pair(private, cert_pem: bytes, cert: str | Path) -> None:
    from cryptography import x509
    from cryptography.hazmat.primitives import serialization

    certificate = x509.load_pem_x509_certificate(cert_pem)
    ours = private.public_key().public_bytes(serialization.Encoding.DER, serialization.PublicFormat.SubjectPublicKeyInfo)
    theirs = certificate.public_key().public_bytes(serialization.Encoding.DER,
                                                   serialization.PublicFormat.SubjectPublicKeyInfo)
    if ours != theirs:
        raise AxiscalError("the certificate is not the private key's: its public key differs", path=cert)


def verify_dcc(dcc: str | Path, cert: str | Path | None = None) -> Verification:
    """Check the signature of a signed DCC.

    Parameters
    ----------
    dcc : str or Path
    cert : str or Path, optional
        The signer's certificate (PEM) to hold the signature against; without it, the certificate
        the DCC carries (which proves the DCC unchanged since signing, not who signed it).

    Returns
    -------
    Verification
        ``valid`` False with the changed parts named when the DCC was changed after signing.

    Raises
    ------
    AxiscalError
        For a file that is not XML or carries no signature.
    """
    from lxml import etree
    from signxml import XMLVerifier
    from signxml.exceptions import InvalidCertificate, InvalidDigest, InvalidInput, InvalidSignature

    from axiscal.io.arguments import check_path

    dcc = check_path("dcc", dcc)
    if cert is not None:
        cert = check_path("cert", cert)
    root = _parse(dcc)
    signature = root.find(f"{{{_DS}}}Signature")
    if signature is None:
        raise AxiscalError("this DCC carries no signature (ds:Signature)", path=dcc)
    cert_pem = _read_pem(cert, "certificate").decode("ascii") if cert is not None else None
    if cert_pem is None:
        text = signature.findtext(f".//{{{_DS}}}X509Certificate")
        if not text:
            raise AxiscalError("the signature carries no certificate: give the signer's certificate (cert)", path=dcc)
        cert_pem = "-----BEGIN CERTIFICATE-----\n" + "".join(text.split()) + "\n-----END CERTIFICATE-----\n"
    signer = _subject(cert_pem)
    try:
        XMLVerifier().verify(etree.tostring(root), x509_cert=cert_pem)
    except (InvalidDigest, InvalidSignature, InvalidCertificate, InvalidInput) as exc:
        stored = {p.get("name"): p.get("sha256") for p in root.iter(f"{{{PARTS_NS}}}part")}
        root.remove(signature)
        now = _parts(root)
        changed = tuple(name for name in sorted(set(stored) | set(now)) if stored.get(name) != now.get(name))
        if isinstance(exc, InvalidDigest) and changed:
            message = "changed after signing: " + ", ".join(changed)
        elif isinstance(exc, InvalidDigest):
            message = "changed after signing (outside the parts axiscal tracks: the digests list or the root)"
        else:
            message = f"the signature does not verify with {signer}'s certificate: {exc}"
        return Verification(False, signer, message, changed)
    return Verification(True, signer, f"signature valid: signed by {signer}, unchanged since signing")


def _subject(cert_pem: str) -> str:
    from cryptography import x509

    try:
        certificate = x509.load_pem_x509_certificate(cert_pem.encode("ascii"))
    except ValueError as exc:
        raise AxiscalError(f"not an X.509 certificate: {exc}") from None
    return certificate.subject.rfc4514_string()
