from setuptools import find_packages, setup

package_name = 'ros2pkg'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='ros2 pkg: list, executables, prefix, xml and create.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'ros2cli.command': ['pkg = ros2pkg.command.pkg:PkgCommand'],
        'ros2cli.extension_point': ['ros2pkg.verb = ros2cli.verb:VerbExtension'],
        'ros2pkg.verb': [
            'create = ros2pkg.verb.create:CreateVerb',
            'executables = ros2pkg.verb.executables:ExecutablesVerb',
            'list = ros2pkg.verb.list:ListVerb',
            'prefix = ros2pkg.verb.prefix:PrefixVerb',
            'xml = ros2pkg.verb.xml:XmlVerb',
        ],
    },
)
