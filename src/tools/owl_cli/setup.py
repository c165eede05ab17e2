from setuptools import find_packages, setup

package_name = 'owl_cli'

# No setup.cfg moving scripts to lib/owl_cli: `owl` goes to the prefix's bin/, which the workspace's
# setup scripts (sourced by env.sh) put on PATH.
setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['windows/static/*']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description=('The owl command: owl check, owl network, owl windows, owl pages, owl class and '
                 'owl demo (the chapter 4 robot live).'),
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'owl = owl_cli.main:main',
        ],
        # owl's commands, as ros2cli's are (owl_cli/command/__init__.py): owl_cli.main lists them.
        'owl_cli.command': [
            'check = owl_cli.check.command:CheckCommand',
            'class = owl_cli.classroom.command:ClassCommand',
            'demo = owl_cli.demo.command:DemoCommand',
            'network = owl_cli.network.command:NetworkCommand',
            'pages = owl_cli.pages.command:PagesCommand',
            'windows = owl_cli.windows.command:WindowsCommand',
        ],
        # owl check's exercises, one plug-in per course section (owl_cli/check/catalogue.py).
        'owl_cli.exercises': [
            '3.4 = owl_cli.check.exercises.section_3_4:SECTION',
            '3.5 = owl_cli.check.exercises.section_3_5:SECTION',
            '3.6 = owl_cli.check.exercises.section_3_6:SECTION',
            '3.7 = owl_cli.check.exercises.section_3_7:SECTION',
            '3.8 = owl_cli.check.exercises.section_3_8:SECTION',
            '3.9 = owl_cli.check.exercises.section_3_9:SECTION',
            '4.3 = owl_cli.check.exercises.section_4_3:SECTION',
            '4.4 = owl_cli.check.exercises.section_4_4:SECTION',
            '4.4.1 = owl_cli.check.exercises.section_4_4_1:SECTION',
            '4.5 = owl_cli.check.exercises.section_4_5:SECTION',
            '4.6 = owl_cli.check.exercises.section_4_6:SECTION',
            '4.7 = owl_cli.check.exercises.section_4_7:SECTION',
        ],
    },
)
