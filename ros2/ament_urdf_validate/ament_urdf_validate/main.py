"""ament_urdf_validate: check a package's robot descriptions with urdf_validate.

Modelled on ament_xmllint: ``main(argv)`` takes paths (default: the current folder, which is the
package's source folder under ``colcon test``), ``--exclude`` names and ``--xunit-file``, and returns
the exit code. Standard library only: it runs in ROS environments.

What is validated is what ``urdf_validate DIR`` discovers: every ``*.urdf``, ``*.sdf`` and ``*.world``,
every ``*.xml`` with a ``<mujoco>`` root, every ``*.xacro`` that builds a robot (macro libraries are
left out); hidden folders and what ``.gitignore`` excludes are skipped. With ``--exclude`` names, or an
``AMENT_IGNORE``/``COLCON_IGNORE`` marker below a folder, or when a folder's only candidates are xacro
files, this module lists that folder's files itself and passes them with ``--skip-xacro-libraries``.

Exit code: 0 when every robot passes (``fail-on = fail``: or only warns), 1 when a robot warns,
2 when one fails or cannot be read, or the validator could not run.
"""

import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from xml.etree import ElementTree

EXPORT_TAG = 'urdf_validate'
EXPORT_ATTRIBUTES = ('args', 'exclude', 'fail-on', 'config')
ROBOT_EXTENSIONS = ('.urdf', '.sdf', '.world', '.xacro')
IGNORE_MARKERS = ('AMENT_IGNORE', 'COLCON_IGNORE')
WARN_LINE = re.compile(r': WARN U\d+ ')


class UsageError(Exception):
    """A mistake in the arguments, package.xml or the environment: one message, exit code 2."""


def main(argv=sys.argv[1:]):
    """Run the linter; return the exit code (0 pass, 1 WARN, 2 FAIL or error)."""
    rc, _errors = main_with_errors(argv)
    return rc


def main_with_errors(argv=sys.argv[1:]):
    """Run the linter; return (exit code, the lines of what made it fail).

    For pytest tests: ``assert rc == 0, '\\n'.join(errors)`` puts the findings (code, file:line:col,
    message) into the failure message, which pytest's JUnit file and ``colcon test-result --verbose``
    show.
    """
    try:
        return _run(argv)
    except UsageError as e:
        message = 'ament_urdf_validate: error: %s' % e
        print(message, file=sys.stderr)
        return 2, [message]


def _parse_args(argv):
    argv = list(argv)
    extra = []
    if '--' in argv:
        at = argv.index('--')
        argv, extra = argv[:at], argv[at + 1:]
    parser = argparse.ArgumentParser(
        prog='ament_urdf_validate',
        description='Check robot descriptions (URDF, xacro, SDFormat, MJCF) with urdf_validate. '
                    'Arguments after -- go to urdf_validate.',
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument(
        'paths', nargs='*', default=[os.curdir],
        help='The files or directories to check. For directories, the robot descriptions urdf_validate '
             'discovers (*.urdf, *.sdf, *.world, *.xacro building a robot, *.xml with a <mujoco> root)')
    parser.add_argument(
        '--exclude', nargs='*', default=[],
        help='Exclude specific file names and directory names from the check')
    parser.add_argument(
        '--xunit-file', help='Generate a xunit compliant XML file')
    parser.add_argument(
        '--config', help='urdf-validate.toml (or pyproject.toml) for every input, instead of the '
                         'nearest one found from each file upwards')
    parser.add_argument(
        '--fail-on', choices=('warn', 'fail'), default=None,
        help='Lowest verdict that fails the check (default: package.xml fail-on, else warn)')
    parser.add_argument(
        '--package-xml', default=None,
        help='package.xml whose <export><urdf_validate .../> holds options '
             '(default: the nearest one from the current folder upwards)')
    args = parser.parse_args(argv)
    args.extra = extra
    return args


def _run(argv):
    start_time = time.time()
    args = _parse_args(argv)

    if args.package_xml and not os.path.isfile(args.package_xml):
        raise UsageError("package.xml '%s' does not exist" % args.package_xml)
    manifest = args.package_xml or find_package_xml(os.getcwd())
    exported = read_export(manifest) if manifest else {}

    fail_on = args.fail_on or exported.get('fail-on') or 'warn'
    excludes = list(args.exclude) + exported.get('exclude', [])
    config = args.config or exported.get('config')
    if config and not os.path.isfile(config):
        raise UsageError("configuration file '%s' does not exist" % config)

    for path in args.paths:
        if not os.path.exists(path):
            raise UsageError("'%s' does not exist (expected a robot description or a folder)" % path)
    inputs, xacro_files_listed = collect_inputs(args.paths, excludes)
    if not inputs or not any(
            os.path.isfile(p) or list_robot_files(p, excludes) for p in inputs):
        print('No files found', file=sys.stderr)
        return 1, ['No robot description files found in %s' % ', '.join(args.paths)]

    binary = find_validator()
    with tempfile.TemporaryDirectory(prefix='ament_urdf_validate_') as out_dir:
        cmd = [binary] + inputs + ['--format', 'text,junit', '--output-dir', out_dir,
                                   '--color', 'never']
        if xacro_files_listed:
            cmd.append('--skip-xacro-libraries')
        if config:
            cmd += ['--config', config]
        cmd += exported.get('args', []) + args.extra
        print('$ ' + ' '.join(shlex.quote(c) for c in cmd), flush=True)
        try:
            proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  universal_newlines=True)
        except OSError as e:
            raise UsageError("could not run '%s': %s" % (binary, e))
        sys.stdout.write(proc.stdout)
        sys.stdout.flush()
        sys.stderr.write(proc.stderr)
        sys.stderr.flush()
        suites = read_junit_files(out_dir)

    validator_rc = proc.returncode
    if validator_rc not in (0, 1, 2):
        rc = 2
    elif validator_rc == 1 and fail_on == 'fail':
        rc = 0
    else:
        rc = validator_rc

    if not suites and validator_rc == 0:
        # Only xacro macro libraries (they build no robot on their own): nothing to fail.
        print('No robot found: the xacro files are macro libraries; nothing to check', flush=True)

    testname = xunit_testname(args.xunit_file) if args.xunit_file else 'urdf_validate'
    cases = convert_cases(suites, testname, fail_on)
    if rc != 0 and not any(c['failure'] or c['error'] for c in cases):
        # The verdict failed without a failing check in the JUnit files (a usage error, a refused
        # input): one error case carrying what the validator said.
        detail = proc.stderr.strip() or proc.stdout.strip()[-2000:]
        cases.append({
            'name': 'urdf_validate', 'classname': testname, 'file': None, 'failure': None,
            'error': 'urdf_validate exited %d: %s' % (validator_rc, detail),
            'skipped': None, 'system_out': None,
        })
    errors = [c['failure'] or c['error'] for c in cases if c['failure'] or c['error']]

    if rc == 0:
        print('No problems found', flush=True)
    else:
        sys.stdout.flush()
        print('%d check(s) failed (fail-on = %s)' % (len(errors), fail_on), file=sys.stderr)

    if args.xunit_file:
        write_xunit(args.xunit_file, testname, cases, sorted({s['file'] for s in suites}),
                    time.time() - start_time)
    return rc, errors


def find_package_xml(folder):
    """Return the nearest package.xml from folder upwards, or None."""
    folder = os.path.abspath(folder)
    while True:
        candidate = os.path.join(folder, 'package.xml')
        if os.path.isfile(candidate):
            return candidate
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


def read_export(manifest):
    """Read ``<export><urdf_validate args=".." exclude=".." fail-on=".." config=".."/>``.

    Paths (config) are relative to the package.xml's folder. Returns a dict; raises UsageError naming
    the file on a malformed package.xml or an unknown attribute.
    """
    try:
        root = ElementTree.parse(manifest).getroot()
    except ElementTree.ParseError as e:
        raise UsageError('%s: not well-formed XML: %s' % (manifest, e))
    except OSError as e:
        raise UsageError('%s: cannot be read: %s' % (manifest, e))
    found = root.findall('export/' + EXPORT_TAG)
    if not found:
        return {}
    if len(found) > 1:
        raise UsageError('%s: more than one <export><%s> element' % (manifest, EXPORT_TAG))
    element = found[0]
    unknown = sorted(set(element.attrib) - set(EXPORT_ATTRIBUTES))
    if unknown:
        raise UsageError('%s: <%s> has unknown attribute(s) %s (known: %s)' % (
            manifest, EXPORT_TAG, ', '.join(unknown), ', '.join(EXPORT_ATTRIBUTES)))
    exported = {}
    try:
        exported['args'] = shlex.split(element.get('args', ''))
    except ValueError as e:
        raise UsageError('%s: <%s args="..."> cannot be split into words: %s' % (
            manifest, EXPORT_TAG, e))
    exported['exclude'] = element.get('exclude', '').split()
    fail_on = element.get('fail-on')
    if fail_on is not None:
        if fail_on not in ('warn', 'fail'):
            raise UsageError('%s: <%s fail-on="%s">: expected warn or fail' % (
                manifest, EXPORT_TAG, fail_on))
        exported['fail-on'] = fail_on
    config = element.get('config')
    if config:
        path = os.path.join(os.path.dirname(manifest), config)
        if not os.path.isfile(path):
            raise UsageError('%s: <%s config="%s">: %s does not exist' % (
                manifest, EXPORT_TAG, config, path))
        exported['config'] = path
    return exported


def find_validator():
    """Return the urdf_validate binary: $URDF_VALIDATE, else urdf_validate on PATH."""
    binary = os.environ.get('URDF_VALIDATE')
    if binary:
        if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
            raise UsageError("URDF_VALIDATE='%s' is not an executable file" % binary)
        return binary
    binary = shutil.which('urdf_validate')
    if not binary:
        raise UsageError("could not find 'urdf_validate' on PATH: install it (cargo install "
                         "--path crates/cli, or pip install urdf-validator) or set URDF_VALIDATE")
    return binary


def collect_inputs(paths, excludes):
    """Return (inputs for urdf_validate, whether xacro files are listed by name).

    A folder is passed as it is (urdf_validate discovers its robots) unless an excluded name or an
    AMENT_IGNORE/COLCON_IGNORE marker lies below it, or its only candidates are xacro files: then its
    candidate files are listed here.
    """
    inputs = []
    listed_xacro = False
    for path in paths:
        if os.path.isfile(path):
            if os.path.basename(path) not in excludes:
                inputs.append(path)
                listed_xacro = listed_xacro or path.endswith('.xacro')
            continue
        if not _needs_listing(path, excludes):
            candidates = list_robot_files(path, excludes)
            # Only xacro files: listed with --skip-xacro-libraries, so that a folder of macro
            # libraries passes (urdf_validate DIR refuses a folder without a robot).
            if not (candidates and all(f.endswith('.xacro') for f in candidates)):
                inputs.append(path)
                continue
        for filename in list_robot_files(path, excludes):
            inputs.append(filename)
            listed_xacro = listed_xacro or filename.endswith('.xacro')
    return inputs, listed_xacro


def _walk(path, excludes):
    for dirpath, dirnames, filenames in os.walk(path):
        if any(m in filenames for m in IGNORE_MARKERS):
            dirnames[:] = []
            continue
        dirnames[:] = sorted(d for d in dirnames if d[0] not in '._' and d not in excludes)
        yield dirpath, sorted(f for f in filenames if f not in excludes)


def _needs_listing(path, excludes):
    for dirpath, dirnames, filenames in os.walk(path):
        dirnames[:] = [d for d in dirnames if not d.startswith('.')]
        names = set(dirnames) | set(filenames)
        if names & set(excludes) or names & set(IGNORE_MARKERS):
            return True
    return False


def list_robot_files(path, excludes):
    """The candidate robot descriptions below path (xacro libraries are left to the validator)."""
    files = []
    for dirpath, filenames in _walk(path, excludes):
        for filename in filenames:
            full = os.path.join(dirpath, filename)
            if filename.endswith(ROBOT_EXTENSIONS) or (
                    filename.endswith('.xml') and _root_tag(full) == 'mujoco'):
                files.append(os.path.normpath(full))
    return files


def _root_tag(path):
    try:
        for _event, element in ElementTree.iterparse(path, events=('start',)):
            return element.tag
    except (ElementTree.ParseError, OSError):
        return None
    return None


def read_junit_files(out_dir):
    """Parse urdf_validate's ``<stem>_validation.xml`` files: one dict per robot suite."""
    suites = []
    for name in sorted(os.listdir(out_dir)):
        if not name.endswith('_validation.xml'):
            continue
        path = os.path.join(out_dir, name)
        try:
            root = ElementTree.parse(path).getroot()
        except ElementTree.ParseError as e:
            raise UsageError('urdf_validate wrote a JUnit file that is not well-formed (%s): %s'
                             % (name, e))
        for suite in root.iter('testsuite'):
            status = None
            for prop in suite.iter('property'):
                if prop.get('name') == 'overall_status':
                    status = prop.get('value')
            suites.append({
                'name': suite.get('name'),
                'file': suite.get('file') or suite.get('name'),
                'status': status,
                'cases': list(suite.iter('testcase')),
            })
    return suites


def convert_cases(suites, testname, fail_on):
    """Turn each robot's checks into test cases of one suite, the finding lines as messages.

    ``colcon test-result --verbose`` prints a failure's ``message`` attribute, not its text: the
    message is the failure's text (``file:line:col: SEVERITY CODE name: message`` per finding). With
    fail-on = warn, a check holding WARN findings fails with those lines.
    """
    cases = []
    for suite in suites:
        for case in suite['cases']:
            converted = {
                'name': '%s: %s' % (suite['file'], case.get('name')),
                'classname': testname,
                'file': suite['file'],
                'failure': None, 'error': None, 'skipped': None, 'system_out': None,
            }
            for child in case:
                text = (child.text or '').strip()
                if child.tag == 'failure':
                    converted['failure'] = text or child.get('message', '')
                elif child.tag == 'error':
                    message = child.get('message', '')
                    converted['error'] = '\n'.join(x for x in (message, text) if x) or 'error'
                elif child.tag == 'skipped':
                    converted['skipped'] = child.get('message', '') or text
                elif child.tag == 'system-out':
                    converted['system_out'] = text
            if fail_on == 'warn' and not converted['failure'] and converted['system_out']:
                warns = [line for line in converted['system_out'].splitlines()
                         if WARN_LINE.search(line)]
                if warns:
                    converted['failure'] = '\n'.join(warns)
                    converted['skipped'] = None
            cases.append(converted)
    return cases


def xunit_testname(xunit_file):
    """``<folder>.<name>`` as the ament linters name their suites (pkg.urdf_validate)."""
    folder_name = os.path.basename(os.path.dirname(os.path.abspath(xunit_file)))
    file_name = os.path.basename(xunit_file)
    for suffix in ('.xml', '.xunit'):
        if file_name.endswith(suffix):
            file_name = file_name[:-len(suffix)]
    return '%s.%s' % (folder_name, file_name)


def write_xunit(path, testname, cases, files, elapsed):
    """Write one ``<testsuite>`` (the ament linters' layout) to path."""
    failures = sum(1 for c in cases if c['failure'])
    errors = sum(1 for c in cases if c['error'] and not c['failure'])
    skipped = sum(1 for c in cases if c['skipped'] and not (c['failure'] or c['error']))
    suite = ElementTree.Element('testsuite', {
        'name': testname, 'tests': str(len(cases)), 'errors': str(errors),
        'failures': str(failures), 'skipped': str(skipped), 'time': '%.3f' % elapsed,
    })
    for c in cases:
        attrs = {'name': c['name'], 'classname': c['classname']}
        element = ElementTree.SubElement(suite, 'testcase', attrs)
        if c['failure']:
            ElementTree.SubElement(element, 'failure', {'message': c['failure']}).text = c['failure']
        elif c['error']:
            ElementTree.SubElement(element, 'error', {'message': c['error']}).text = c['error']
        elif c['skipped']:
            ElementTree.SubElement(element, 'skipped', {'message': c['skipped']})
        if c['system_out']:
            ElementTree.SubElement(element, 'system-out').text = c['system_out']
    ElementTree.SubElement(suite, 'system-out').text = 'Checked files:' + ''.join(
        '\n* %s' % f for f in files)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    if hasattr(ElementTree, 'indent'):  # Python 3.9+
        ElementTree.indent(suite)
    ElementTree.ElementTree(suite).write(path, encoding='UTF-8', xml_declaration=True)


if __name__ == '__main__':
    sys.exit(main())
